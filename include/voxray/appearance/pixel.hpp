// What the compositing walk returns for one ray, on every backend (appearance/walk.inc):
// layout-compatible with the kernels' vx_app_walk_result (pixel_layout.h).
#pragma once
#include <cstddef>
#include <cstdint>
#include <limits>

#include "voxray/appearance/pixel_layout.h"
#include "voxray/core/ray_hit_layout.h"

namespace voxray {

struct appearance_pixel {
    float r = 0, g = 0, b = 0;  // linear colour, blended front to back
    float transmittance = 1;    // what is left of the ray: 1 for a miss
    float t = std::numeric_limits<float>::infinity();  // the first voxel's entry t
    std::int32_t x = 0, y = 0, z = 0;                  // the first voxel
    std::uint32_t face = VX_FACE_NONE;                 // how the first voxel was entered
    std::uint32_t material = 0;                        // the first voxel's palette index
    std::uint32_t visits = 0;                          // voxels blended
    std::uint32_t steps = 0;                           // structure kernel steps, every re-entry
    std::uint32_t status = VX_STATUS_MISS;             // or VX_APP_WALK_NO_RECORD
    float nx = 0, ny = 0, nz = 0;                      // blended normal, length 1 - transmittance at most

    bool is_hit() const { return status == VX_STATUS_HIT; }
};

static_assert(sizeof(appearance_pixel) == VX_APP_PIXEL_BYTES);
static_assert(offsetof(appearance_pixel, r) == VX_APP_PIXEL_OFFSET_COLOUR);
static_assert(offsetof(appearance_pixel, transmittance) == VX_APP_PIXEL_OFFSET_TRANSMITTANCE);
static_assert(offsetof(appearance_pixel, t) == VX_APP_PIXEL_OFFSET_T);
static_assert(offsetof(appearance_pixel, x) == VX_APP_PIXEL_OFFSET_VOXEL);
static_assert(offsetof(appearance_pixel, face) == VX_APP_PIXEL_OFFSET_FACE);
static_assert(offsetof(appearance_pixel, material) == VX_APP_PIXEL_OFFSET_MATERIAL);
static_assert(offsetof(appearance_pixel, visits) == VX_APP_PIXEL_OFFSET_VISITS);
static_assert(offsetof(appearance_pixel, steps) == VX_APP_PIXEL_OFFSET_STEPS);
static_assert(offsetof(appearance_pixel, status) == VX_APP_PIXEL_OFFSET_STATUS);
static_assert(offsetof(appearance_pixel, nx) == VX_APP_PIXEL_OFFSET_NORMAL);

}  // namespace voxray
