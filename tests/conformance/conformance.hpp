// The conformance suite: edge cases, agreement (oracle, reference, cpu_scalar bit for
// bit) and incremental edits, typed over (backend, structure). Every structure comes
// from the generated type list voxray::registered::structures, so registering a
// structure (one voxray_add_structure line in CMake) enters it here with no test edit.
// Beyond voxray::structure the suite needs what the tool needs too: construction from a
// voxel_model, bounds(), and for an editable_structure apply() of every region kind.
//
//   VOXRAY_CONFORMANCE(prefix, backend...)
//
// instantiates every suite for each backend x registered structure (one .cpp per
// backend group: test_cpu.cpp, test_opencl.cpp, test_vulkan.cpp).
#pragma once
#include "agreement.hpp"
#include "edge_cases.hpp"
#include "edits.hpp"
#include "typed_cases.hpp"
#include "voxray/generated/structures.hpp"

#define VOXRAY_CONFORMANCE(prefix, ...)                                                                 \
    using prefix##_cases = ::voxray::test::cases_t<::voxray::registered::structures, __VA_ARGS__>;     \
    INSTANTIATE_TYPED_TEST_SUITE_P(prefix, edge_cases, prefix##_cases, ::voxray::test::case_names);     \
    INSTANTIATE_TYPED_TEST_SUITE_P(prefix, agreement_suite, prefix##_cases, ::voxray::test::case_names); \
    INSTANTIATE_TYPED_TEST_SUITE_P(prefix, edit_suite, prefix##_cases, ::voxray::test::case_names)
