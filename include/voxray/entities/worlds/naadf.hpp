// Scenes over naadf worlds: scene<W> (entities/scene.hpp) for every W traced by the naadf
// kernel, and its scene kernel (entities/worlds/naadf.h), registered by voxray_add_scene(naadf)
// in CMakeLists.txt.
#pragma once
#include "voxray/naadf/naadf.hpp"
#include "voxray/entities/scene.hpp"
#include "voxray/entities/scene_hit.hpp"

#define VOXRAY_KERNEL_NAME scene_naadf
#define VOXRAY_KERNEL_FILE "voxray/entities/worlds/naadf.h"
#include "voxray/kernels/kernel_tag.inc"

namespace voxray {

template <>
struct scene_kernel_of<kernels::naadf_kernel> {
    using type = kernels::scene_naadf_kernel;
};

}  // namespace voxray
