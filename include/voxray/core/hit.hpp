// What a trace returns. Layout-compatible with the kernels' vx_hit.
#pragma once
#include <cstddef>
#include <cstdint>
#include <limits>

#include <glm/vec3.hpp>

#include "voxray/core/ray_hit_layout.h"

namespace voxray {

// The face a ray entered the hit voxel through, as its outward normal.
enum class face : std::uint32_t {
    pos_x = VX_FACE_POS_X, neg_x = VX_FACE_NEG_X,
    pos_y = VX_FACE_POS_Y, neg_y = VX_FACE_NEG_Y,
    pos_z = VX_FACE_POS_Z, neg_z = VX_FACE_NEG_Z,
    inside = VX_FACE_INSIDE,  // the ray started (at tmin) inside this solid voxel
    none = VX_FACE_NONE,      // miss
};

// Unit normal of a face; zero for inside/none.
inline glm::vec3 face_normal(face f) {
    switch (f) {
    case face::pos_x: return {1, 0, 0};
    case face::neg_x: return {-1, 0, 0};
    case face::pos_y: return {0, 1, 0};
    case face::neg_y: return {0, -1, 0};
    case face::pos_z: return {0, 0, 1};
    case face::neg_z: return {0, 0, -1};
    default: return {0, 0, 0};
    }
}

inline const char* face_name(face f) {
    static const char* names[] = {"+x", "-x", "+y", "-y", "+z", "-z", "inside", "none"};
    auto i = static_cast<std::uint32_t>(f);
    return i < 8 ? names[i] : "invalid";
}

struct hit {
    float t = std::numeric_limits<float>::infinity();  // ray parameter of the entry point
    glm::ivec3 voxel{0};                               // world voxel coordinate
    face normal = face::none;
    std::uint32_t material = 0;  // palette index, 1..255; 0 on a miss
    std::uint32_t steps = 0;     // traversal steps taken: a machine-independent cost
    std::uint32_t status = VX_STATUS_MISS;

    bool is_hit() const { return status == VX_STATUS_HIT; }
};

static_assert(sizeof(hit) == VX_HIT_BYTES);
static_assert(offsetof(hit, t) == VX_HIT_OFFSET_T);
static_assert(offsetof(hit, voxel) == VX_HIT_OFFSET_VOXEL);
static_assert(offsetof(hit, normal) == VX_HIT_OFFSET_FACE);
static_assert(offsetof(hit, material) == VX_HIT_OFFSET_MATERIAL);
static_assert(offsetof(hit, steps) == VX_HIT_OFFSET_STEPS);
static_assert(offsetof(hit, status) == VX_HIT_OFFSET_STATUS);

}  // namespace voxray
