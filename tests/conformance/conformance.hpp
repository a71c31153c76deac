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

namespace voxray::test {

// The registered structures whose hits carry palette indices, as the reference's do. A
// structure with material_is_colour (the DAG's colour blocks) is held to the same
// geometry with colours within its error instead: tests/svdag and `voxray check`.
template <class List>
struct index_material_structures;
template <class... S>
struct index_material_structures<type_list<S...>> {
    template <class One>
    static constexpr bool colour = requires { One::material_is_colour; };
    using type = concat_type_lists_t<std::conditional_t<colour<S>, type_list<>, type_list<S>>...>;
};

}  // namespace voxray::test

#define VOXRAY_CONFORMANCE(prefix, ...)                                                                 \
    using prefix##_cases = ::voxray::test::cases_t<                                                   \
        ::voxray::test::index_material_structures<::voxray::registered::structures>::type, __VA_ARGS__>; \
    INSTANTIATE_TYPED_TEST_SUITE_P(prefix, edge_cases, prefix##_cases, ::voxray::test::case_names);     \
    INSTANTIATE_TYPED_TEST_SUITE_P(prefix, agreement_suite, prefix##_cases, ::voxray::test::case_names); \
    INSTANTIATE_TYPED_TEST_SUITE_P(prefix, edit_suite, prefix##_cases, ::voxray::test::case_names)
