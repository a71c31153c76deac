// Convex edit regions for brickmap::apply. A region answers three questions, all in
// exact integer arithmetic so that a reference model receiving the same edit agrees
// voxel for voxel:
//   exact_bounds()          the voxels it may touch (min inclusive, max exclusive), in
//                           64 bits: a radius of INT_MAX reaches past int coordinates;
//   bounds()                the same saturated to int coordinates (what fits a box3i);
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

#include <glm/common.hpp>
#include <glm/ext/vector_int3_sized.hpp>
#include <glm/vector_relational.hpp>
#include <glm/vec3.hpp>

#include "voxray/core/box.hpp"
#include "voxray/edit/wide_math.hpp"

namespace voxray::regions {

// A box in 64-bit coordinates (min inclusive, max exclusive): region bounds before they
// are known to fit 32-bit voxel coordinates.
struct box64 {
    glm::i64vec3 min{0}, max{0};
    bool empty() const { return max.x <= min.x || max.y <= min.y || max.z <= min.z; }
    bool inside(const box3i& b) const {
        return empty() || (glm::all(glm::greaterThanEqual(min, glm::i64vec3(b.min))) &&
                           glm::all(glm::lessThanEqual(max, glm::i64vec3(b.max))));
    }
    // Clamped to int coordinates.
    box3i saturated() const {
        auto clamp = [](glm::i64vec3 v) {
            return glm::ivec3(glm::clamp(v, glm::i64vec3(INT32_MIN), glm::i64vec3(INT32_MAX)));
        };
        return {clamp(min), clamp(max)};
    }
};

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
    box64 exact_bounds() const { return {b.min, b.max}; }
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
    box64 exact_bounds() const {
        glm::i64vec3 c(centre);
        return {c - std::int64_t(radius), c + (std::int64_t(radius) + 1)};
    }
    box3i bounds() const { return exact_bounds().saturated(); }
    // Offsets reach 2^32 and radii 2^31: an offset beyond the radius is outside before
    // anything is squared, so squares stay below 2^62 and their sum below 2^64.
    bool contains(glm::ivec3 p) const {
        if (radius < 0) return false;
        glm::i64vec3 d = glm::abs(glm::i64vec3(p) - glm::i64vec3(centre));
        if (d.x > radius || d.y > radius || d.z > radius) return false;
        return std::uint64_t(d.x * d.x) + std::uint64_t(d.y * d.y) + std::uint64_t(d.z * d.z) <= r2();
    }
    std::pair<int, int> span(int y, int z, int x0, int x1) const {
        std::int64_t dy = std::int64_t(y) - centre.y, dz = std::int64_t(z) - centre.z;
        if (radius < 0 || dy > radius || -dy > radius || dz > radius || -dz > radius) return {0, 0};
        std::int64_t rest = std::int64_t(r2()) - dy * dy - dz * dz;
        if (rest < 0) return {0, 0};
        std::int64_t dx = isqrt(rest);
        return {int(std::max<std::int64_t>(x0, centre.x - dx)), int(std::min<std::int64_t>(x1, centre.x + dx + 1))};
    }
    bool touches(const box3i& q) const {
        if (radius < 0) return false;
        std::uint64_t d2 = 0;
        for (int a = 0; a < 3; ++a) {
            std::int64_t lo = q.min[a], hi = std::int64_t(q.max[a]) - 1, c = centre[a];
            std::int64_t d = c < lo ? lo - c : (c > hi ? c - hi : 0);
            if (d > radius) return false;
            d2 += std::uint64_t(d * d);
        }
        return d2 <= r2();
    }
    std::uint64_t r2() const { return std::uint64_t(std::int64_t(radius) * radius); }
};

// A thick line: voxels p whose squared distance to segment [a, b] is <= radius^2,
// computed exactly (t = dot(p - a, b - a) / |b - a|^2 is clamped by comparing
// numerators; the distance is compared scaled by |b - a|^2, in 256 bits: endpoints
// anywhere in int coordinates, radius up to INT_MAX).
// For a one-voxel-thick line use brickmap::apply_line(a, b, ...), a 3D DDA walk.
struct capsule {
    glm::ivec3 a{0}, b{0};
    int radius = 0;
    box64 exact_bounds() const {
        return {glm::i64vec3(glm::min(a, b)) - std::int64_t(radius), glm::i64vec3(glm::max(a, b)) + (std::int64_t(radius) + 1)};
    }
    box3i bounds() const { return exact_bounds().saturated(); }
    bool contains(glm::ivec3 p) const {
        if (radius < 0) return false;
        // Components below 2^33: dot products below 3 * 2^66, exact in 128 bits.
        auto dot = [](glm::i64vec3 u, glm::i64vec3 v) { return i128(u.x) * v.x + i128(u.y) * v.y + i128(u.z) * v.z; };
        glm::i64vec3 ab = glm::i64vec3(b) - glm::i64vec3(a), ap = glm::i64vec3(p) - glm::i64vec3(a);
        i128 len2 = dot(ab, ab), t = dot(ap, ab), r2 = i128(radius) * radius;
        if (len2 == 0 || t <= 0) return dot(ap, ap) <= r2;
        if (t >= len2) {
            glm::i64vec3 bp = glm::i64vec3(p) - glm::i64vec3(b);
            return dot(bp, bp) <= r2;
        }
        // |ap|^2 - t^2 / len2 <= r2   <=>   |ap|^2 * len2 <= r2 * len2 + t^2
        return mul_wide(u128(dot(ap, ap)), u128(len2)) <= mul_wide(u128(r2), u128(len2)) + mul_wide(abs_wide(t), abs_wide(t));
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

// The voxels of line_voxels(a, b) that lie in `clip`, in the same order, without walking
// the parts outside (a line from x = -2e9 to 2e9 through a small world costs the world's
// width, not 4e9 steps). Voxel i of the walk has major coordinate a + s * i and minor
// offsets floor((2 d i + n - 1) / 2n): Bresenham's error terms in closed form.
template <class F>
void line_voxels_in(glm::ivec3 a, glm::ivec3 b, const box3i& clip, F&& f) {
    if (clip.empty()) return;
    glm::i64vec3 d = glm::abs(glm::i64vec3(b) - glm::i64vec3(a));
    glm::i64vec3 s{b.x > a.x ? 1 : -1, b.y > a.y ? 1 : -1, b.z > a.z ? 1 : -1};
    int major = d.x >= d.y && d.x >= d.z ? 0 : (d.y >= d.z ? 1 : 2);
    std::int64_t n = d[major];
    // Steps whose major coordinate lies in the clip box.
    std::int64_t lo = clip.min[major], hi = std::int64_t(clip.max[major]) - 1, a0 = a[major];
    std::int64_t first = s[major] > 0 ? lo - a0 : a0 - hi, last = s[major] > 0 ? hi - a0 : a0 - lo;
    first = std::max<std::int64_t>(first, 0);
    last = std::min(last, n);
    for (std::int64_t i = first; i <= last; ++i) {
        glm::i64vec3 p;
        for (int k = 0; k < 3; ++k) {
            std::int64_t steps = k == major || n == 0 ? (k == major ? i : 0)
                                                      : std::int64_t((i128(2) * d[k] * i + n - 1) / (i128(2) * n));
            p[k] = std::int64_t(a[k]) + s[k] * steps;
        }
        if (glm::all(glm::greaterThanEqual(p, glm::i64vec3(clip.min))) && glm::all(glm::lessThan(p, glm::i64vec3(clip.max))))
            f(glm::ivec3(p));
    }
}

}  // namespace voxray::regions
