// Ray sets aimed at the places where a traversal's float rules show: lattice points and
// the 26 lattice directions, rays running exactly along voxel planes and edges, tiny,
// huge, zero and denormal direction components, and rays that are invalid in one field.
#pragma once
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "voxray/check/ray_sets.hpp"
#include "voxray/core/box.hpp"
#include "voxray/core/ray.hpp"

namespace voxray::test {

// From every lattice point of b grown by one, in all 26 directions of {-1,0,1}^3:
// origins on faces, edges and corners, rays along faces and through edges. Each also
// from the cell centre with a finite [tmin, tmax].
inline std::vector<ray> lattice_rays(box3i b) {
    std::vector<ray> rays;
    for (int z = b.min.z - 1; z <= b.max.z + 1; ++z)
        for (int y = b.min.y - 1; y <= b.max.y + 1; ++y)
            for (int x = b.min.x - 1; x <= b.max.x + 1; ++x)
                for (int d = 0; d < 27; ++d) {
                    glm::vec3 dir(d % 3 - 1, d / 3 % 3 - 1, d / 9 - 1);
                    if (dir == glm::vec3(0.0f)) continue;
                    rays.push_back(ray{glm::vec3(x, y, z), 0.0f, dir, INFINITY});
                    rays.push_back(ray{glm::vec3(x, y, z) + 0.5f, 0.25f, dir, 3.0f});
                }
    return rays;
}

// Rays exactly in a voxel plane (one origin coordinate an integer, that direction
// component zero) or along a voxel edge (two of each), at random places and slopes in
// and around b; both signs of zero.
inline std::vector<ray> grazing_rays(box3i b, std::size_t count, std::uint64_t seed) {
    rng g(seed);
    glm::ivec3 e = glm::max(b.extent(), glm::ivec3(1));
    std::vector<ray> rays(count);
    for (auto& r : rays) {
        int fixed = 1 + g.below(2), first = g.below(3);
        for (int a = 0; a < 3; ++a) {
            r.origin[a] = g.uniform(float(b.min[a] - 2), float(b.max[a] + 2));
            r.direction[a] = g.uniform(-1.0f, 1.0f);
        }
        for (int k = 0; k < fixed; ++k) {
            int a = (first + k) % 3;
            r.origin[a] = float(b.min[a] + g.below(e[a] + 1));
            r.direction[a] = g.below(2) ? 0.0f : -0.0f;
        }
        if (g.below(4) == 0) r.origin = glm::floor(r.origin);  // from a lattice point
        if (r.direction == glm::vec3(0.0f)) r.direction[(first + 2) % 3] = 1.0f;
        r.tmax = g.below(4) == 0 ? g.uniform(0.5f, float(e.x + e.y + e.z)) : INFINITY;
    }
    return rays;
}

// Origins on b's planes, at zero of either sign, or random around b; each direction
// component either one of `components` or random in [-1, 1]; tmin = +0 or -0.
inline std::vector<ray> extreme_rays(box3i b, std::span<const float> components, std::size_t count,
                                     std::uint64_t seed) {
    std::vector<ray> rays;
    rng g(seed);
    for (std::size_t i = 0; i < count; ++i) {
        ray r;
        for (int a = 0; a < 3; ++a) {
            float lo = float(b.min[a]), hi = float(b.max[a]);
            const float at[] = {lo, lo + 0.5f, 0.0f, -0.0f, hi - 0.001f, hi, lo - 12.0f};
            r.origin[a] = g.below(2) ? at[g.below(7)] : g.uniform(lo - 4.0f, hi + 4.0f);
            r.direction[a] = g.below(2) ? components[std::size_t(g.below(int(components.size())))]
                                        : g.uniform(-1.0f, 1.0f);
        }
        r.tmin = g.below(4) ? 0.0f : -0.0f;
        rays.push_back(r);
    }
    return rays;
}

// Rays from far away (origins up to 3e38) with components at the edges of the DDA's
// rules: just below and just above VX_MIN_DIRECTION (2^-120, about 7.5e-37, under which a
// component counts as zero), 1e-38, 1e-30, and ordinary ones; half of them aimed at a point
// of box b. Crossing t then overflows float for many, which must give a miss, never a
// hit at t = inf; and a component that counts as zero must not move the walk at all.
inline std::vector<ray> far_rays(box3i b, std::size_t count, std::uint64_t seed) {
    static constexpr float far[] = {1e30f, -1e30f, 1e20f, -1e20f, 1e7f, -1e7f, 3e38f, -3e38f};
    static constexpr float tiny[] = {1e-38f, -1e-38f, 7.523e-37f, -7.523e-37f, 7.53e-37f, -7.53e-37f,
                                     1e-30f, -1e-30f, 0.0f, 1.0f, -1.0f};
    std::vector<ray> rays;
    rng g(seed);
    for (std::size_t i = 0; i < count; ++i) {
        ray r;
        glm::vec3 target;
        for (int a = 0; a < 3; ++a) {
            float lo = float(b.min[a]), hi = float(b.max[a]);
            target[a] = g.uniform(lo, hi);
            r.origin[a] = g.below(2) ? far[g.below(8)] : g.uniform(lo - 4.0f, hi + 4.0f);
            r.direction[a] = tiny[g.below(11)];
        }
        if (g.below(2)) r.direction = target - r.origin;
        rays.push_back(r);
    }
    return rays;
}

// Rays from above box b that enter its top face on a y plane (a multiple of 4: block,
// chunk and page planes of every structure), heading to -y, kept where float rounding puts
// the walk's start cell on the far side of that plane although the plane's crossing comes
// first (the start cell is floor(o + d t) at the entry t; the crossing is (plane - o) / d).
// Every walk must then step y at the entry t. NAADF once carried such a ray out of the world
// instead (1 ray of 2 M on sibenik at 1024). The test computes both as the DDA's begin does,
// unfused (volatile), in world coordinates with b.min = 0.
inline std::vector<ray> entry_on_plane_rays(box3i b, std::size_t count, std::uint64_t seed) {
    std::vector<ray> rays;
    rng g(seed);
    for (std::size_t tries = 0; rays.size() < count && tries < 400 * count; ++tries) {
        float top = float(b.max.z), height = g.uniform(10.0f, 900.0f);
        float x = g.uniform(float(b.min.x), float(b.max.x));
        float y = float(b.min.y + 4 * (1 + g.below(std::max(1, b.extent().y / 4 - 1))));
        glm::vec3 d(g.uniform(-1.0f, 1.0f), g.uniform(-1.0f, -0.05f), -1.0f);
        ray r{glm::vec3(x, y, top) - d * height, 0.0f, d, INFINITY};
        volatile float inv_z = 1.0f / r.direction.z, inv_y = 1.0f / r.direction.y;
        volatile float entry = (top - r.origin.z) * inv_z;
        volatile float moved = r.direction.y * entry;
        volatile float py = r.origin.y + moved;
        volatile float crossing = (y - r.origin.y) * inv_y;
        if (std::floor(py) == y && crossing < entry) rays.push_back(r);
    }
    return rays;
}

inline constexpr float huge_and_tiny_components[] = {0.0f, -0.0f, 1e-30f, -1e-30f, 1.0f, -1.0f, 3e38f, -3e38f};
// Denormals (|d| < 2^-126: 1/d overflows) must act as zero in every DDA.
inline constexpr float denormal_components[] = {0.0f, -0.0f, 1e-40f, -1e-40f, -1e-38f, 1.0f, -1.0f};

// Rays aimed straight at voxel `target` from `from`, each made invalid by one field:
// NaN or Inf in origin, direction or tmin, NaN tmax, a zero or denormal-only direction,
// tmin > tmax. The first ray is the valid one they were made from.
inline std::vector<ray> invalid_rays(glm::vec3 from, glm::vec3 to) {
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = INFINITY;
    ray good{from, 0.0f, to - from, inf};
    std::vector<ray> rays(15, good);
    rays[1].origin.y = nan;
    rays[2].origin.x = -inf;
    rays[3].origin.z = inf;
    rays[4].direction.x = nan;
    rays[5].direction.x = inf;
    rays[6].direction.z = -inf;
    rays[7].tmin = nan;
    rays[8].tmin = -inf;
    rays[9].tmin = inf;
    rays[10].tmax = nan;
    rays[11].direction = glm::vec3(0.0f);
    rays[12].direction = glm::vec3(-0.0f, 0.0f, -0.0f);
    rays[13].direction = glm::vec3(1e-40f, -1e-39f, 0.0f);
    rays[14].tmin = 3.0f, rays[14].tmax = 2.0f;
    return rays;
}

// check_rays (camera views and random rays) and as many random_rays again.
inline std::vector<ray> mixed_rays(const box3i& bounds, std::size_t n, std::uint64_t seed) {
    auto rays = check_rays(bounds, 2, n, seed);
    auto more = random_rays(bounds, n, seed + 100);
    rays.insert(rays.end(), more.begin(), more.end());
    return rays;
}

}  // namespace voxray::test
