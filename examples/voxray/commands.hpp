// The subcommands of the voxray tool; each returns the process exit code.
#pragma once
#include <glm/vec3.hpp>

namespace voxray::tool {

int run_info(int argc, char** argv);
int run_render(int argc, char** argv);
int run_check(int argc, char** argv);
int run_bench(int argc, char** argv);

// The render's light, also used for benchmark shadow rays (defined in render.cpp).
glm::vec3 light_direction(int up_axis);

}  // namespace voxray::tool
