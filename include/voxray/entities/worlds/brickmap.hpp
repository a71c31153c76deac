// Scenes over brickmap worlds: scene<W> (entities/scene.hpp) for every W traced by the brickmap
// kernel, and its scene kernel (entities/worlds/brickmap.h), registered by voxray_add_scene(brickmap)
// in CMakeLists.txt.
#pragma once
#include "voxray/brickmap/brickmap.hpp"
#include "voxray/entities/scene.hpp"
#include "voxray/entities/scene_hit.hpp"

#define VOXRAY_KERNEL_NAME scene_brickmap
#define VOXRAY_KERNEL_FILE "voxray/entities/worlds/brickmap.h"
#include "voxray/kernels/kernel_tag.inc"

namespace voxray {

template <>
struct scene_kernel_of<kernels::brickmap_kernel> {
    using type = kernels::scene_brickmap_kernel;
};

}  // namespace voxray
