// Scenes over naadf worlds: scene<naadf> (entities/scene.hpp) and its kernel
// (entities/worlds/naadf.h), registered by voxray_add_scene(naadf) in CMakeLists.txt.
#pragma once
#include "voxray/naadf/naadf.hpp"
#include "voxray/entities/scene.hpp"
#include "voxray/entities/scene_hit.hpp"

#define VOXRAY_KERNEL_NAME scene_naadf
#define VOXRAY_KERNEL_FILE "voxray/entities/worlds/naadf.h"
#include "voxray/kernels/kernel_tag.inc"

namespace voxray {

template <>
struct scene_kernel_of<naadf> {
    using type = kernels::scene_naadf_kernel;
};

}  // namespace voxray
