// Includes the Vulkan backend without linking voxray::vulkan: must fail to compile, naming
// the target to link (not compile and then fail to link with undefined Vulkan symbols).
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/vulkan.hpp"

int main() {
    voxray::voxel_model model;
    model.set({0, 0, 0}, 1);
    voxray::dense_grid grid(model);
    voxray::tracer<voxray::vulkan, voxray::dense_grid> tracer(grid);
    return 0;
}
