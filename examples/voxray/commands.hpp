// What the subcommands share beyond the command line.
#pragma once
#include <glm/vec3.hpp>

namespace voxray::tool {

// The render's light, also used for benchmark shadow rays (defined in render.cpp).
glm::vec3 light_direction(int up_axis);

}  // namespace voxray::tool
