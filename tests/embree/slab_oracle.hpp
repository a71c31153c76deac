// A brute-force oracle for small models: slab-test every solid voxel in double precision and
// take the smallest entry t. Independent of the code under test (no DDA, no BVH, no shared
// helpers), and it knows which answers are ties: voxels entered within a tolerance of the
// first hit, faces entered on the same t (edges, corners), and "marginal" hits that a float
// implementation may see or miss (a ray grazing an edge, an entry right at tmax).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/vec3.hpp>

#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::test {

struct oracle_candidate {
    glm::ivec3 voxel;
    std::uint32_t material;
    double t;             // entry parameter, clamped to tmin
    std::uint32_t faces;  // bit f: entering through face f is acceptable (ties on an edge)
    bool strict;          // hit under exact arithmetic
    bool marginal;        // within tolerance of being a miss
};

struct oracle_answer {
    bool valid = false;   // false: a miss by contract (NaN, zero direction, ...)
    bool inside = false;  // start point in a solid voxel
    float tmin = 0.0f;
    glm::ivec3 start{0};
    std::uint32_t start_material = 0;
    std::vector<oracle_candidate> candidates;  // every voxel touched within tolerance
    double first = std::numeric_limits<double>::infinity();           // min t, strict hits
    double first_definite = std::numeric_limits<double>::infinity();  // min t, non-marginal
};

inline double tolerance(double t) { return 1e-4 * std::max(1.0, std::abs(t)); }

class slab_oracle {
public:
    explicit slab_oracle(const voxel_model& m) : model_(m) {
        m.for_each_voxel([&](glm::ivec3 p, std::uint8_t v) { voxels_.push_back({p, v}); });
    }

    oracle_answer trace(const ray& r) const {
        oracle_answer a;
        auto finite = [](glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); };
        if (!finite(r.origin) || !finite(r.direction) || !std::isfinite(r.tmin) || std::isnan(r.tmax)) return a;
        if (r.direction == glm::vec3(0.0f) || !(r.tmin <= r.tmax)) return a;
        // The contract's start point is the float o + tmin * d.
        glm::vec3 p = r.tmin == 0.0f ? r.origin : r.origin + r.tmin * r.direction;
        if (!finite(p)) return a;
        a.valid = true;
        a.tmin = r.tmin;
        glm::dvec3 pd(p);
        if (std::abs(pd.x) < 1e9 && std::abs(pd.y) < 1e9 && std::abs(pd.z) < 1e9) {
            a.start = glm::ivec3(std::floor(pd.x), std::floor(pd.y), std::floor(pd.z));
            a.start_material = model_.get(a.start);
            a.inside = a.start_material != 0;
        }
        const glm::dvec3 o(r.origin), d(r.direction);
        const double tmin = r.tmin, tmax = r.tmax;
        for (auto& [v, m] : voxels_) {
            double t0 = -INFINITY, t1 = INFINITY;
            double t_in[3] = {-INFINITY, -INFINITY, -INFINITY};
            bool out = false;
            for (int k = 0; k < 3 && !out; ++k) {
                double lo = v[k], hi = v[k] + 1.0;
                if (d[k] == 0.0) {
                    out = !(o[k] >= lo && o[k] < hi);
                    continue;
                }
                double a0 = (lo - o[k]) / d[k], a1 = (hi - o[k]) / d[k];
                t_in[k] = std::min(a0, a1);
                t0 = std::max(t0, t_in[k]);
                t1 = std::min(t1, std::max(a0, a1));
            }
            if (out) continue;
            double tol = tolerance(std::max(std::abs(t0), std::abs(tmin)));
            bool loose = t0 <= t1 + tol && t1 > tmin - tol && t0 <= tmax + tol;
            if (!loose) continue;
            oracle_candidate c;
            c.voxel = v;
            c.material = m;
            c.t = std::max(t0, tmin);
            c.strict = t0 <= t1 && t1 > tmin && t0 <= tmax;
            double margin = std::min({t1 - t0, t1 - tmin, tmax - t0});
            c.marginal = margin <= tol;
            c.faces = 0;
            for (int k = 0; k < 3; ++k)
                if (d[k] != 0.0 && t_in[k] >= t0 - tol) c.faces |= 1u << (2 * k + (d[k] > 0 ? 1 : 0));
            // Entering at tmin from a start on the voxel's boundary: the face crossed there.
            if (t0 < tmin)
                for (int k = 0; k < 3; ++k)
                    if (d[k] != 0.0 && t_in[k] >= tmin - tol) c.faces |= 1u << (2 * k + (d[k] > 0 ? 1 : 0));
            if (c.strict) a.first = std::min(a.first, c.t);
            if (c.strict && !c.marginal) a.first_definite = std::min(a.first_definite, c.t);
            a.candidates.push_back(c);
        }
        return a;
    }

private:
    const voxel_model& model_;
    std::vector<std::pair<glm::ivec3, std::uint8_t>> voxels_;
};

enum class verdict { exact, tie, wrong };

// Judges a closest hit against the oracle.
inline verdict judge_closest(const oracle_answer& a, const hit& h) {
    auto is_miss = [](const hit& x) {
        return x.status == VX_STATUS_MISS && x.normal == face::none && std::isinf(x.t) && x.t > 0 && x.material == 0;
    };
    if (!a.valid) return is_miss(h) ? verdict::exact : verdict::wrong;
    if (a.inside) {
        bool ok = h.is_hit() && h.voxel == a.start && h.normal == face::inside && h.material == a.start_material;
        return ok && h.t == a.tmin ? verdict::exact : verdict::wrong;
    }
    if (!h.is_hit()) {
        if (!is_miss(h)) return verdict::wrong;
        if (std::isinf(a.first)) return verdict::exact;
        return std::isinf(a.first_definite) ? verdict::tie : verdict::wrong;
    }
    for (auto& c : a.candidates) {
        if (c.voxel != h.voxel) continue;
        auto f = static_cast<std::uint32_t>(h.normal);
        bool face_ok = f < 6 && (c.faces >> f) & 1u;
        bool t_ok = std::abs(double(h.t) - c.t) <= tolerance(c.t) && c.t <= a.first_definite + tolerance(c.t);
        if (!face_ok || !t_ok || h.material != c.material) return verdict::wrong;
        bool unique_face = (c.faces & (c.faces - 1)) == 0;
        bool first = c.strict && !c.marginal && c.t == a.first && unique_face;
        // Exact when no other candidate lies within tolerance of this one.
        for (auto& o : a.candidates)
            if (o.voxel != c.voxel && std::abs(o.t - c.t) <= tolerance(c.t)) first = false;
        return first ? verdict::exact : verdict::tie;
    }
    return verdict::wrong;
}

// Judges an any-hit result. With `full_record` the hit must also name a voxel on the ray
// (box scene); otherwise only the status is checked (quad scene).
inline verdict judge_any(const oracle_answer& a, const hit& h, bool full_record) {
    if (!a.valid) return h.status == VX_STATUS_MISS ? verdict::exact : verdict::wrong;
    if (a.inside) {
        if (!h.is_hit()) return verdict::wrong;
        if (!full_record) return verdict::exact;
        // Any solid voxel on the ray will do; the start voxel is the natural one.
        if (h.voxel == a.start) return h.normal == face::inside && h.t == a.tmin ? verdict::exact : verdict::wrong;
    }
    if (!h.is_hit()) {
        if (std::isinf(a.first)) return verdict::exact;
        return std::isinf(a.first_definite) ? verdict::tie : verdict::wrong;
    }
    if (!full_record) {
        if (!std::isinf(a.first_definite)) return verdict::exact;
        return a.candidates.empty() ? verdict::wrong : verdict::tie;
    }
    for (auto& c : a.candidates) {
        if (c.voxel != h.voxel) continue;
        auto f = static_cast<std::uint32_t>(h.normal);
        bool ok = f < 6 && (c.faces >> f) & 1u && std::abs(double(h.t) - c.t) <= tolerance(c.t) &&
                  h.material == c.material;
        if (!ok) return verdict::wrong;
        return c.strict && !c.marginal ? verdict::exact : verdict::tie;
    }
    return verdict::wrong;
}

}  // namespace voxray::test
