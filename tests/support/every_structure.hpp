// Typed tests over every registered structure (voxray::registered::structures, generated
// from the voxray_add_structure calls), named by the structure ("dense", "svdag_colours",
// "world_16", ...): a new structure enters every such test with no test edit.
#pragma once
#include "typed_cases.hpp"
#include "voxray/generated/structures.hpp"

namespace voxray::test {

using every_structure = gtest_types<registered::structures>::type;
using structure_names = type_names;

}  // namespace voxray::test
