// Convex edit regions for brickmap::apply. A region answers three questions, all in
// exact integer arithmetic so that a reference model receiving the same edit agrees
// voxel for voxel:
//   bounds()                the voxels it may touch (min inclusive, max exclusive);
//   contains(p)             whether voxel p is inside;
//   span(y, z, x0, x1)      the x interval [a, b) of row (y, z) inside the region,
//                           clipped to [x0, x1) (convex: one interval per row);
//   touches(box)            a cheap conservative test that lets whole bricks be skipped.
// Convexity also means a brick whose 8 corner voxels are inside lies wholly inside:
// apply() uses that to turn a covered brick into a solid (or empty) top cell directly.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include <glm/ext/vector_int3_sized.hpp>
#include <glm/vec3.hpp>

#include "voxray/core/box.hpp"

namespace voxray::regions {

// Largest s with s * s <= v (v >= 0).
inline std::int64_t isqrt(std::int64_t v) {
    auto s = std::int64_t(std::sqrt(double(v)));
    while (s * s > v) --s;
    while ((s + 1) * (s + 1) <= v) ++s;
    return s;
}

struct box {
    box3i b;
    box3i bounds() const { return b; }
    bool contains(glm::ivec3 p) const { return b.contains(p); }
    std::pair<int, int> span(int y, int z, int x0, int x1) const {
        if (y < b.min.y || y >= b.max.y || z < b.min.z || z >= b.max.z) return {0, 0};
        return {std::max(x0, b.min.x), std::min(x1, b.max.x)};
    }
    bool touches(const box3i& q) const { return !box3i{glm::max(q.min, b.min), glm::min(q.max, b.max)}.empty(); }
};

// Voxels p with |p - centre|^2 <= radius^2 (voxel coordinates, integers).
struct sphere {
    glm::ivec3 centre{0};
    int radius = 0;
    box3i bounds() const { return {centre - radius, centre + radius + 1}; }
    bool contains(glm::ivec3 p) const {
        glm::i64vec3 d = glm::i64vec3(p) - glm::i64vec3(centre);
        return d.x * d.x + d.y * d.y + d.z * d.z <= std::int64_t(radius) * radius;
    }
    std::pair<int, int> span(int y, int z, int x0, int x1) const {
        std::int64_t dy = y - centre.y, dz = z - centre.z;
        std::int64_t rest = std::int64_t(radius) * radius - dy * dy - dz * dz;
        if (rest < 0) return {0, 0};
        auto dx = int(isqrt(rest));
        return {std::max(x0, centre.x - dx), std::min(x1, centre.x + dx + 1)};
    }
    bool touches(const box3i& q) const {
        std::int64_t d2 = 0;
        for (int a = 0; a < 3; ++a) {
            std::int64_t lo = q.min[a], hi = q.max[a] - 1, c = centre[a];
            std::int64_t d = c < lo ? lo - c : (c > hi ? c - hi : 0);
            d2 += d * d;
        }
        return d2 <= std::int64_t(radius) * radius;
    }
};

// A thick line: voxels p whose squared distance to segment [a, b] is <= radius^2,
// computed exactly in 64-bit integers (t = dot(p - a, b - a) / |b - a|^2 is clamped
// by comparing numerators; the distance is compared scaled by |b - a|^4).
// For a one-voxel-thick line use brickmap::apply_line(a, b, ...), a 3D DDA walk.
struct capsule {
    glm::ivec3 a{0}, b{0};
    int radius = 0;
    box3i bounds() const { return {glm::min(a, b) - radius, glm::max(a, b) + radius + 1}; }
    bool contains(glm::ivec3 p) const {
        glm::i64vec3 ab = glm::i64vec3(b) - glm::i64vec3(a), ap = glm::i64vec3(p) - glm::i64vec3(a);
        std::int64_t len2 = ab.x * ab.x + ab.y * ab.y + ab.z * ab.z;
        std::int64_t r2 = std::int64_t(radius) * radius;
        std::int64_t t = ap.x * ab.x + ap.y * ab.y + ap.z * ab.z;
        if (len2 == 0 || t <= 0) return ap.x * ap.x + ap.y * ap.y + ap.z * ap.z <= r2;
        if (t >= len2) {
            glm::i64vec3 bp = glm::i64vec3(p) - glm::i64vec3(b);
            return bp.x * bp.x + bp.y * bp.y + bp.z * bp.z <= r2;
        }
        // |ap|^2 - t^2 / len2 <= r2   <=>   |ap|^2 * len2 - t^2 <= r2 * len2  (in 128 bits)
        __int128 lhs = __int128(ap.x * ap.x + ap.y * ap.y + ap.z * ap.z) * len2 - __int128(t) * t;
        return lhs <= __int128(r2) * len2;
    }
    std::pair<int, int> span(int y, int z, int x0, int x1) const {
        // The row meets the convex capsule in one interval: scan it from both ends
        // inside the bounds (rows are at most a brick wide when called from apply).
        auto bb = bounds();
        int lo = std::max(x0, bb.min.x), hi = std::min(x1, bb.max.x);
        if (y < bb.min.y || y >= bb.max.y || z < bb.min.z || z >= bb.max.z) return {0, 0};
        while (lo < hi && !contains({lo, y, z})) ++lo;
        while (hi > lo && !contains({hi - 1, y, z})) --hi;
        return {lo, hi};
    }
    bool touches(const box3i& q) const {
        auto bb = bounds();
        return !box3i{glm::max(q.min, bb.min), glm::min(q.max, bb.max)}.empty();
    }
};

}  // namespace voxray::regions

namespace voxray::regions {

// The voxels of a one-voxel-thick line from a to b (both included): a 3D DDA in integer
// arithmetic (Bresenham's error terms along the dominant axis), so every caller and
// every reference walks exactly the same voxels. f(p) is called once per voxel.
template <class F>
void line_voxels(glm::ivec3 a, glm::ivec3 b, F&& f) {
    glm::i64vec3 d = glm::abs(glm::i64vec3(b) - glm::i64vec3(a));
    glm::ivec3 s{b.x > a.x ? 1 : -1, b.y > a.y ? 1 : -1, b.z > a.z ? 1 : -1};
    int major = d.x >= d.y && d.x >= d.z ? 0 : (d.y >= d.z ? 1 : 2);
    int u = (major + 1) % 3, v = (major + 2) % 3;
    std::int64_t n = d[major];
    std::int64_t eu = 2 * d[u] - n, ev = 2 * d[v] - n;
    glm::ivec3 p = a;
    for (std::int64_t i = 0;; ++i) {
        f(p);
        if (i == n) break;
        if (eu > 0) { p[u] += s[u]; eu -= 2 * n; }
        if (ev > 0) { p[v] += s[v]; ev -= 2 * n; }
        eu += 2 * d[u];
        ev += 2 * d[v];
        p[major] += s[major];
    }
}

}  // namespace voxray::regions
