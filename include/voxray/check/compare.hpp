// How two hits for the same ray are judged against each other (`voxray check`, tests).
//
//  same      both miss, or both hit the same voxel through the same face with the same
//            material and t within tolerance;
//  tie       both hit at the same t within tolerance, but a different voxel or face: the
//            ray passes through an edge or corner where several voxels start at that t;
//            or the earlier of two answers (or the only hit) is a voxel the ray merely
//            grazes: its path inside that voxel is no longer than the tolerance, so float
//            rounding decides whether it touches the voxel at all;
//  mismatch  anything else (a hit against a miss, a different t, a different material
//            on the same voxel).
//
// Tolerance is in world units along the ray: 1e-3 voxel plus 4e-6 of the distance from the
// world origin, covering float rounding of entry points in worlds up to 2^16 voxels.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>

#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/model/palette.hpp"

namespace voxray {

enum class agreement { same, tie, mismatch };

inline float t_tolerance(const ray& r, float t) {
    float len = glm::length(r.direction);
    if (!(len > 0.0f) || !std::isfinite(len)) return 0.0f;
    float reach = glm::length(r.origin) + std::abs(t) * len;
    return (1e-3f + 4e-6f * reach) / len;
}

// Length (in t) of the ray's path through the box of voxel v; negative when it misses.
inline float path_through_voxel(const ray& r, glm::ivec3 v) {
    float t0 = -INFINITY, t1 = INFINITY;
    for (int a = 0; a < 3; ++a) {
        float lo = float(v[a]), hi = float(v[a] + 1), o = r.origin[a], d = r.direction[a];
        if (d == 0.0f) {
            if (o < lo || o > hi) return -1.0f;
            continue;
        }
        float ta = (lo - o) / d, tb = (hi - o) / d;
        t0 = std::max(t0, std::min(ta, tb));
        t1 = std::min(t1, std::max(ta, tb));
    }
    return t1 - std::max(t0, r.tmin);
}

// Whether hit h is on a voxel the ray only grazes (an edge or corner within tolerance).
inline bool grazes(const ray& r, const hit& h) {
    return h.is_hit() && h.normal != face::inside && path_through_voxel(r, h.voxel) <= 2.0f * t_tolerance(r, h.t);
}

inline agreement compare_hits(const ray& r, const hit& reference, const hit& other) {
    if (!reference.is_hit() && !other.is_hit()) return agreement::same;
    if (reference.is_hit() != other.is_hit()) {
        // A hit exactly at tmax may fall on either side of the limit.
        const hit& h = reference.is_hit() ? reference : other;
        bool at_limit = std::abs(h.t - r.tmax) <= t_tolerance(r, h.t);
        return at_limit || grazes(r, h) ? agreement::tie : agreement::mismatch;
    }
    bool t_close = std::abs(reference.t - other.t) <= t_tolerance(r, reference.t);
    if (!t_close) return grazes(r, reference.t < other.t ? reference : other) ? agreement::tie : agreement::mismatch;
    if (reference.voxel == other.voxel) {
        if (reference.material != other.material) return agreement::mismatch;
        return reference.normal == other.normal ? agreement::same : agreement::tie;
    }
    return agreement::tie;
}

// For a structure whose hits carry RGBA8 colours instead of palette indices (the sparse
// voxel DAG's colour blocks): the geometry is judged as above, and on the same voxel the
// colour must lie within `tolerance` (per channel, in [0, 1]) of the palette colour of the
// reference's material, or the hit is a mismatch.
inline agreement compare_colour_hits(const ray& r, const hit& reference, hit other, const palette& p, double tolerance) {
    if (reference.is_hit() && other.is_hit() && reference.voxel == other.voxel) {
        if (colour_difference(other.material, p[std::uint8_t(reference.material)].colour) > tolerance)
            return agreement::mismatch;
        other.material = reference.material;
    }
    return compare_hits(r, reference, other);
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
