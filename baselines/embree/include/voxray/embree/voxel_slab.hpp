// Exact ray / unit-voxel test used by the box scene's Embree callbacks: where a ray first
// meets voxel v = [v, v+1)^3 within [tnear, tfar], and through which face.
//
// Rules, chosen to agree with the reference DDA:
//  - Inside starts are the caller's business (the box scene looks the start voxel up before
//    tracing); this test only answers "where does the ray enter v".
//  - An axis with zero direction never enters or leaves the slab: the ray is in it when its
//    origin coordinate o lies in [v, v+1), half-open like the voxel. A ray running exactly
//    along the plane x = v+1 therefore belongs to the next voxel, as in the DDA.
//  - Otherwise the usual slab intervals, closed: a ray through an edge or corner of v counts
//    as touching it (the contract allows any of the voxels tied at an edge).
//  - Each plane's t is (plane - o) / d with a true division, so two neighbours sharing a
//    plane compute the same t bit for bit and never both miss a ray between them.
//  - Equal entry t on several axes (an edge or corner) picks the lower face id.
#pragma once
#include <cstdint>
#include <limits>

#include <glm/vec3.hpp>

#include "voxray/core/ray_hit_layout.h"

namespace voxray::embree {

struct voxel_entry {
    bool hit = false;
    float t = 0.0f;
    std::uint32_t face = VX_FACE_NONE;
};

// o, d: the ray as Embree traces it; tnear/tfar: its current interval (tfar shrinks as
// closer hits are found).
inline voxel_entry enter_voxel(glm::vec3 o, glm::vec3 d, float tnear, float tfar, glm::ivec3 v) {
    float t0 = -std::numeric_limits<float>::infinity();  // latest entry over the axes
    float t1 = std::numeric_limits<float>::infinity();   // earliest exit
    std::uint32_t face = VX_FACE_NONE;
    for (int a = 0; a < 3; ++a) {
        float lo = float(v[a]), hi = float(v[a] + 1);
        if (d[a] == 0.0f) {
            if (!(o[a] >= lo && o[a] < hi)) return {};
            continue;
        }
        float t_lo = (lo - o[a]) / d[a];
        float t_hi = (hi - o[a]) / d[a];
        // Moving +a the ray enters through the low plane, whose outward normal is -a.
        std::uint32_t entry_face = d[a] > 0.0f ? std::uint32_t(2 * a + 1) : std::uint32_t(2 * a);
        float t_in = d[a] > 0.0f ? t_lo : t_hi;
        float t_out = d[a] > 0.0f ? t_hi : t_lo;
        // Axes are visited in increasing face id, so a strict > keeps the lower id on a tie.
        if (t_in > t0) { t0 = t_in; face = entry_face; }
        if (t_out < t1) t1 = t_out;
    }
    // Leaving exactly at tnear means the ray starts on v's far side, moving away: no hit.
    // An entry at t = inf (a denormal direction) is no entry.
    if (!(t0 <= t1) || !(t1 > tnear) || !(t0 <= tfar) || !(t0 < std::numeric_limits<float>::infinity())) return {};
    // A start point on v's near boundary (or a rounding hair inside it) that the floor rule
    // put in the neighbour is an entry at tnear through the face that was crossed.
    return {true, t0 > tnear ? t0 : tnear, face};
}

}  // namespace voxray::embree
