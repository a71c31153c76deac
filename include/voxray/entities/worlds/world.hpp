// Scenes over world worlds: scene<W> (entities/scene.hpp) for every W traced by the world
// kernel, and its scene kernel (entities/worlds/world.h), registered by voxray_add_scene(world)
// in CMakeLists.txt.
#pragma once
#include "voxray/world/world.hpp"
#include "voxray/entities/scene.hpp"
#include "voxray/entities/scene_hit.hpp"

#define VOXRAY_KERNEL_NAME scene_world
#define VOXRAY_KERNEL_FILE "voxray/entities/worlds/world.h"
#include "voxray/kernels/kernel_tag.inc"

namespace voxray {

template <>
struct scene_kernel_of<kernels::world_kernel> {
    using type = kernels::scene_world_kernel;
};

}  // namespace voxray
