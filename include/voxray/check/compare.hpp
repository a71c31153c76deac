// How two hits for the same ray are judged against each other (`voxray check`, tests).
//
//  same      both miss, or both hit the same voxel through the same face with the same
//            material and t within tolerance;
//  tie       both hit at the same t within tolerance, but a different voxel or face: the
//            ray passes through an edge or corner where several voxels start at that t;
//  mismatch  anything else (a hit against a miss, a different t, a different material
//            on the same voxel).
//
// Tolerance is in world units along the ray: 1e-3 voxel plus 4e-6 of the distance from the
// world origin, covering float rounding of entry points in worlds up to 2^16 voxels.
#pragma once
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"

namespace voxray {

enum class agreement { same, tie, mismatch };

inline float t_tolerance(const ray& r, float t) {
    float len = glm::length(r.direction);
    if (!(len > 0.0f) || !std::isfinite(len)) return 0.0f;
    float reach = glm::length(r.origin) + std::abs(t) * len;
    return (1e-3f + 4e-6f * reach) / len;
}

inline agreement compare_hits(const ray& r, const hit& reference, const hit& other) {
    if (!reference.is_hit() && !other.is_hit()) return agreement::same;
    if (reference.is_hit() != other.is_hit()) {
        // A hit exactly at tmax may fall on either side of the limit.
        const hit& h = reference.is_hit() ? reference : other;
        return std::abs(h.t - r.tmax) <= t_tolerance(r, h.t) ? agreement::tie : agreement::mismatch;
    }
    bool t_close = std::abs(reference.t - other.t) <= t_tolerance(r, reference.t);
    if (!t_close) return agreement::mismatch;
    if (reference.voxel == other.voxel) {
        if (reference.material != other.material) return agreement::mismatch;
        return reference.normal == other.normal ? agreement::same : agreement::tie;
    }
    return agreement::tie;
}

struct agreement_counts {
    std::uint64_t rays = 0, same = 0, ties = 0, mismatches = 0;

    void add(agreement a) {
        ++rays;
        if (a == agreement::same) ++same;
        else if (a == agreement::tie) ++ties;
        else ++mismatches;
    }
};

}  // namespace voxray
