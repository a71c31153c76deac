// What a raster frame of chunk meshes shows at one pixel (the identity attachment of
// voxray/vulkan/chunk_raster.hpp): the voxel and face of the quad drawn there. At level
// of detail 0 it is what the ray tracer's primary hit through the pixel's centre reports
// (check/raster_hits.hpp compares the two).
#pragma once
#include <cstdint>

#include <glm/vec3.hpp>

#include "voxray/core/ray_hit_layout.h"

namespace voxray {

struct raster_pixel {
    glm::ivec3 voxel{0};
    std::uint32_t face = VX_FACE_NONE;  // VX_FACE_*; VX_FACE_NONE where nothing was drawn
};

}  // namespace voxray
