// An oracle independent of every DDA: slab-test each solid voxel of a small model and
// keep the smallest entry t. Used to check the reference grid itself.
#pragma once
#include <cmath>

#include <glm/common.hpp>
#include <vector>

#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::test {

inline hit brute_force_trace(const voxel_model& model, const ray& r) {
    hit best;
    auto bad = [](float v) { return !std::isfinite(v); };
    if (bad(r.origin.x) || bad(r.origin.y) || bad(r.origin.z) || bad(r.direction.x) || bad(r.direction.y) ||
        bad(r.direction.z) || bad(r.tmin) || std::isnan(r.tmax) || r.tmin > r.tmax ||
        (r.direction == glm::vec3(0.0f)))
        return best;
    // Cells are half-open, so the voxel containing the point at tmin is the one the ray
    // starts in, even when the ray leaves it at once through a corner.
    glm::ivec3 start(glm::floor(r.origin + r.direction * r.tmin));
    if (auto m = model.get(start)) {
        best.t = r.tmin;
        best.voxel = start;
        best.material = m;
        best.status = VX_STATUS_HIT;
        best.normal = face::inside;
        return best;
    }
    model.for_each_voxel([&](glm::ivec3 v, std::uint8_t material) {
        float t0 = -INFINITY, t1 = INFINITY;
        int axis = -1;
        for (int a = 0; a < 3; ++a) {
            float o = r.origin[a], d = r.direction[a], lo = float(v[a]), hi = float(v[a] + 1);
            if (d == 0.0f) {
                if (o < lo || o >= hi) return;
                continue;
            }
            float ta = (lo - o) / d, tb = (hi - o) / d;
            float n = std::min(ta, tb), f = std::max(ta, tb);
            if (n > t0) { t0 = n; axis = a; }
            t1 = std::min(t1, f);
        }
        float t = std::max(t0, r.tmin);
        // A ray that only touches an edge or corner (zero length inside) does not hit.
        if (!(t < t1) || t > r.tmax || t >= best.t) return;
        best.t = t;
        best.voxel = v;
        best.material = material;
        best.status = VX_STATUS_HIT;
        if (t0 < r.tmin) best.normal = face::inside;
        else best.normal = static_cast<face>(axis * 2 + (r.direction[axis] > 0 ? 1 : 0));
    });
    return best;
}

}  // namespace voxray::test
