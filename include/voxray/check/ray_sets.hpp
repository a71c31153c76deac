// Ray sets shared by `voxray check`, `voxray bench` and the tests: camera rays from
// several views and random rays (origins inside and outside the scene, axis-parallel and
// zero-component directions, finite and infinite tmax). Cameras, diffuse bounces and
// shadow rays are the public helpers of voxray/rays.hpp.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "voxray/core/box.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/rays.hpp"

namespace voxray {

// Random rays around a box. A quarter start inside it, the rest up to half a box outside;
// an eighth are axis-parallel, an eighth have one zero direction component; a quarter
// have a finite tmax; some origins sit exactly on voxel corners.
inline std::vector<ray> random_rays(const box3i& bounds, std::size_t count, std::uint64_t seed) {
    rng g(seed);
    glm::vec3 lo(bounds.min), hi(bounds.max);
    glm::vec3 size = glm::max(hi - lo, glm::vec3(1.0f));
    std::vector<ray> rays(count);
    for (auto& r : rays) {
        int kind = g.below(8);
        float margin = kind < 2 ? 0.0f : 0.5f;
        for (int a = 0; a < 3; ++a) r.origin[a] = g.uniform(lo[a] - margin * size[a], hi[a] + margin * size[a]);
        if (kind == 2) r.origin = glm::floor(r.origin);  // on a voxel corner
        if (kind == 3) {  // axis-parallel, either sign
            r.direction = glm::vec3(0.0f);
            r.direction[g.below(3)] = g.below(2) ? 1.0f : -1.0f;
        } else {
            glm::vec3 target;
            for (int a = 0; a < 3; ++a) target[a] = g.uniform(lo[a], hi[a]);
            r.direction = target - r.origin;
            if (kind == 4) r.direction[g.below(3)] = 0.0f;  // one zero component
            if (glm::length(r.direction) == 0.0f) r.direction = glm::vec3(1.0f, 0.0f, 0.0f);
            r.direction = glm::normalize(r.direction);
        }
        r.tmin = kind == 5 ? g.uniform(0.0f, 0.5f * size.x) : 0.0f;
        r.tmax = g.below(4) == 0 ? g.uniform(1.0f, 2.0f * glm::length(size)) : INFINITY;
    }
    return rays;
}

// Camera rays from `views` automatic views, `per_view` rays each on a square-ish grid.
inline std::vector<ray> camera_rays(const box3i& bounds, int up_axis, int views, std::size_t per_view) {
    std::vector<ray> rays;
    int side = std::max(1, int(std::sqrt(double(per_view))));
    for (int v = 0; v < views; ++v) {
        auto view = primary_rays(auto_camera(bounds, up_axis, v), side, side);
        rays.insert(rays.end(), view.begin(), view.end());
    }
    return rays;
}

// The `voxray check` mix: half camera rays from 4 views, half random rays.
inline std::vector<ray> check_rays(const box3i& bounds, int up_axis, std::size_t count, std::uint64_t seed) {
    auto rays = camera_rays(bounds, up_axis, 4, count / 8);
    auto random = random_rays(bounds, count - std::min(count, rays.size()), seed);
    rays.insert(rays.end(), random.begin(), random.end());
    rays.resize(count);
    return rays;
}

}  // namespace voxray
