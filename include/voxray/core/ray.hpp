// A ray in world (voxel) units: one unit is one voxel edge. Layout-compatible with
// the kernels' vx_ray (see core/ray_hit_layout.h), so spans of rays go to any backend
// without conversion.
#pragma once
#include <cstddef>
#include <limits>

#include <glm/vec3.hpp>

#include "voxray/core/ray_hit_layout.h"

namespace voxray {

struct ray {
    glm::vec3 origin{0.0f};
    float tmin = 0.0f;
    glm::vec3 direction{0.0f, 0.0f, 1.0f};  // need not be normalized; t is in units of |direction|
    float tmax = std::numeric_limits<float>::infinity();
};

static_assert(sizeof(ray) == VX_RAY_BYTES);
static_assert(offsetof(ray, origin) == VX_RAY_OFFSET_ORIGIN);
static_assert(offsetof(ray, tmin) == VX_RAY_OFFSET_TMIN);
static_assert(offsetof(ray, direction) == VX_RAY_OFFSET_DIRECTION);
static_assert(offsetof(ray, tmax) == VX_RAY_OFFSET_TMAX);

}  // namespace voxray
