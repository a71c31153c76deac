// Typed tests over every tracer backend the test program links: the list is
// voxray::registered::backends (the CPU lanes always; OpenCL and Vulkan where the program
// links them), so a new backend enters every such test with no test edit.
//
//   template <class Backend> struct my_suite : ::testing::Test {};
//   TYPED_TEST_SUITE(my_suite, every_backend, backend_names);
//   TYPED_TEST(my_suite, claim) { ... TypeParam ... }   // runs as my_suite/vulkan.claim
#pragma once

#include <gtest/gtest.h>

#include "typed_cases.hpp"
#include "voxray/generated/backends.hpp"

namespace voxray::test {

using every_backend = gtest_types<registered::backends>::type;

// Test names: the backend's name ("cpu_scalar" for "cpu-scalar").
using backend_names = type_names;

}  // namespace voxray::test
