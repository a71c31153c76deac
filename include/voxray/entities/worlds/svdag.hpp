// Scenes over svdag worlds: scene<W> (entities/scene.hpp) for every W traced by the svdag
// kernel, and its scene kernel (entities/worlds/svdag.h), registered by voxray_add_scene(svdag)
// in CMakeLists.txt.
#pragma once
#include "voxray/svdag/svdag.hpp"
#include "voxray/entities/scene.hpp"
#include "voxray/entities/scene_hit.hpp"

#define VOXRAY_KERNEL_NAME scene_svdag
#define VOXRAY_KERNEL_FILE "voxray/entities/worlds/svdag.h"
#include "voxray/kernels/kernel_tag.inc"

namespace voxray {

template <>
struct scene_kernel_of<kernels::svdag_kernel> {
    using type = kernels::scene_svdag_kernel;
};

}  // namespace voxray
