// The *faithful* record (appearance/layout.h) of one voxel: the paper's virtual octahedron
// (sections 3.2 and 3.3) and its 3x3x3 subgrid of opacities (section 3.4), built as the
// paper and its published code describe, to be compared with ours in the same harness.
// Where the two differ, the code's rule is taken (its figures came from it): three extremal
// normals 120 degrees apart on the cone of a face's normals, at least 0.1 rad wide; a face is
// a fixed set when its normals fall into at most 3 directions 5 degrees apart.
// Departures, both forced: the sampling rays are this project's (sampling_rays.hpp, the
// same for every record); a ray's first hit is looked for inside the voxel only, against
// every triangle, since no per-voxel triangle list is kept (the paper also counts a hit on
// one of the voxel's own triangles before the ray enters it, as occlusion).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "voxray/appearance/layout.h"
#include "voxray/appearance/record_codes.hpp"
#include "voxray/appearance/sggx.hpp"
#include "voxray/appearance/voxel_sampler.hpp"

namespace voxray::appearance {

using faithful_words = std::array<std::uint32_t, VX_APP_FAITHFUL_WORDS>;

// The subgrid element (x + 3 y + 9 z) of a point of the unit cube.
inline unsigned subgrid_element(glm::dvec3 q) {
    auto cell = [](double c) { return unsigned(std::clamp(int(std::floor(c * 3.0)), 0, 2)); };
    return cell(q.x) + 3u * cell(q.y) + 9u * cell(q.z);
}

// The elements (bit e) that the segment from p (in the unit cube) along unit d crosses for
// `length`: the pieces between the planes x, y, z = 1/3, 2/3, each found by its midpoint.
inline std::uint32_t crossed_elements(glm::dvec3 p, glm::dvec3 d, double length) {
    std::vector<double> cuts{0.0, length};  // at most 8
    for (int a = 0; a < 3; ++a)
        for (double plane : {1.0 / 3.0, 2.0 / 3.0})
            if (d[a] != 0.0) {
                double t = (plane - p[a]) / d[a];
                if (t > 0.0 && t < length) cuts.push_back(t);
            }
    std::sort(cuts.begin(), cuts.end());
    std::uint32_t mask = 0;
    for (std::size_t i = 1; i < cuts.size(); ++i)
        if (cuts[i] - cuts[i - 1] > 1e-9) mask |= 1u << subgrid_element(p + d * (0.5 * (cuts[i] + cuts[i - 1])));
    return mask;
}

// What the paper gathers for a voxel: the samples, and per subgrid element the rays that
// crossed it, the ones of those that stopped in the voxel, and whether a front-facing hit
// point lies in it.
struct faithful_samples {
    std::vector<surface_sample> seen;
    std::array<std::uint32_t, VX_APP_FAITHFUL_ELEMENTS> rays{}, stopped{};
    std::uint32_t holds_hit = 0;  // bit e
    std::uint32_t hits = 0;       // rays stopped in the voxel
};

template <class Surfaces>
faithful_samples sample_faithful(const Surfaces& surfaces, glm::ivec3 voxel, const sampling_options& o) {
    faithful_samples out;
    const voxel_rays rays(voxel, o.rays, o.stratified, o.seed);
    for (std::uint32_t i = 0; i < o.rays; ++i) {
        sampling_ray r = rays(i);
        segment_hit h = surfaces.first_surface(r.origin, r.direction, r.length);
        glm::dvec3 local = r.origin - glm::dvec3(voxel);
        // The code's rule: a ray counts in every element its line crosses, also past its hit.
        std::uint32_t crossed = crossed_elements(local, r.direction, r.length);
        for (unsigned e = 0; e < VX_APP_FAITHFUL_ELEMENTS; ++e)
            if (crossed >> e & 1u) out.rays[e] += 1, out.stopped[e] += h.hit ? 1u : 0u;
        out.hits += h.hit ? 1u : 0u;
        if (!h.sample) continue;
        out.seen.push_back(h.seen);
        out.holds_hit |= 1u << subgrid_element(local + r.direction * std::clamp(double(h.t), 0.0, r.length));
    }
    return out;
}

// A face's normals as the paper stores them: up to 3 directions as they are (a fixed set),
// else 3 extremal normals 120 degrees apart on the cone around their mean.
struct face_normals {
    std::array<glm::dvec3, 3> normals{};
    unsigned stored = 3;  // 1..3 for a fixed set
    bool fixed = false;
};

inline face_normals paper_face_normals(const std::vector<glm::dvec3>& normals) {
    face_normals f;
    const double together = std::cos(5.0 * std::numbers::pi / 180.0);
    std::vector<glm::dvec3> directions;
    for (glm::dvec3 n : normals) {
        bool known = false;
        for (glm::dvec3 d : directions) known = known || glm::dot(n, d) >= together;
        if (!known) directions.push_back(n);
        if (directions.size() > 3) break;
    }
    if (directions.size() <= 3) {
        f.fixed = true, f.stored = unsigned(directions.size());
        for (std::size_t k = 0; k < 3; ++k) f.normals[k] = directions[std::min(k, directions.size() - 1)];
        return f;
    }
    glm::dvec3 sum(0.0);
    for (glm::dvec3 n : normals) sum += n;
    glm::dvec3 mean = glm::length(sum) > 1e-9 ? glm::normalize(sum) : normals.front();
    double widest = 0.1;  // the code's least opening
    for (glm::dvec3 n : normals) widest = std::max(widest, std::acos(std::clamp(glm::dot(n, mean), -1.0, 1.0)));
    glm::dvec3 side = std::fabs(mean.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    glm::dvec3 u = glm::normalize(glm::cross(mean, side)), v = glm::cross(mean, u);
    for (int k = 0; k < 3; ++k) {
        double phi = 2.0 * std::numbers::pi * k / 3.0;
        f.normals[std::size_t(k)] =
            std::cos(widest) * mean + std::sin(widest) * (std::cos(phi) * u + std::sin(phi) * v);
    }
    return f;
}

inline std::uint32_t snorm8_vec(glm::dvec3 n, std::uint32_t top_byte) {
    return snorm(float(n.x), 8) | snorm(float(n.y), 8) << 8 | snorm(float(n.z), 8) << 16 | top_byte << 24;
}

inline faithful_words make_faithful_record(const faithful_samples& s) {
    faithful_words w{};
    std::vector<glm::dvec3> normals;
    for (const surface_sample& x : s.seen) normals.push_back(glm::dvec3(x.normal));
    sggx_fit fit = fit_sggx(normals);
    // The octahedron's vertex on axis a: the SGGX's "point on the surface" along it,
    // sqrt(p_b p_c / p_a) / sqrt(pi) for projected areas p; only the ratios matter.
    glm::dvec3 p = fit.projected, reach(std::sqrt(p.y * p.z / p.x), std::sqrt(p.x * p.z / p.y),
                                        std::sqrt(p.x * p.y / p.z));
    double longest = std::max({reach.x, reach.y, reach.z});
    for (int a = 0; a < 3; ++a)
        w[std::size_t(a)] = snorm8_vec(fit.frame[std::size_t(a)],
                                       std::max<std::uint32_t>(1u, unorm(reach[a] / longest, 255)));
    std::array<std::vector<std::size_t>, 8> members;
    for (std::size_t i = 0; i < normals.size(); ++i) members[std::size_t(fit.octant(normals[i]))].push_back(i);
    std::uint32_t flags = 0;
    for (unsigned f = 0; f < 8; ++f) {
        if (members[f].empty()) continue;
        std::vector<glm::dvec3> mine;
        glm::dvec4 colour(0.0);
        for (std::size_t i : members[f]) mine.push_back(normals[i]), colour += glm::dvec4(s.seen[i].colour);
        colour /= double(mine.size());
        face_normals fn = paper_face_normals(mine);
        std::uint32_t code[3] = {srgb_code(colour.r), srgb_code(colour.g), srgb_code(colour.b)};
        for (unsigned k = 0; k < 3; ++k)
            w[VX_APP_FAITHFUL_FACE_WORD(f, k)] = snorm8_vec(fn.normals[k], code[k]);
        flags |= 1u << f;
        if (fn.fixed) flags |= 1u << (8 + f) | (fn.stored & 3u) << (16 + 2 * f);
    }
    w[VX_APP_FAITHFUL_FLAGS_WORD] = flags;
    for (unsigned e = 0; e < VX_APP_FAITHFUL_ELEMENTS; ++e) {
        bool keeps = (s.holds_hit >> e & 1u) != 0 && s.rays[e] > 0;  // the paper's last pass
        std::uint32_t q = keeps ? unorm(double(s.stopped[e]) / double(s.rays[e]), 255) : 0u;
        w[VX_APP_FAITHFUL_OPACITY_WORD + e / 4] |= q << (8 * (e % 4));
    }
    return w;
}

}  // namespace voxray::appearance
