// Scenes over dense_grid worlds: scene<W> (entities/scene.hpp) for every W traced by the dense_grid
// kernel, and its scene kernel (entities/worlds/dense_grid.h), registered by voxray_add_scene(dense_grid)
// in CMakeLists.txt.
#pragma once
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/entities/scene.hpp"
#include "voxray/entities/scene_hit.hpp"

#define VOXRAY_KERNEL_NAME scene_dense_grid
#define VOXRAY_KERNEL_FILE "voxray/entities/worlds/dense_grid.h"
#include "voxray/kernels/kernel_tag.inc"

namespace voxray {

template <>
struct scene_kernel_of<kernels::dense_grid_kernel> {
    using type = kernels::scene_dense_grid_kernel;
};

}  // namespace voxray
