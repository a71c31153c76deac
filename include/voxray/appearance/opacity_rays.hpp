// A voxel's opacity along the 13 opacity directions (layout.h): for each, the share of a
// stratified set of parallel rays through the voxel's projection that meet a surface
// inside it. The rays enter through each face the direction sees (1, 2 or 3 of them, all
// with the same projected area, as every component is 0 or +-1) at the jittered centres of
// an n x n grid, so the share is the covered part of the silhouette, with no thickening of
// thin surfaces (the paper's 3^3 subgrid widens them; see docs/appearance.md). A ray counts
// with its coverage: 1 on a triangle, 0..1 through a finer level's filtered voxels. A
// direction and its opposite see the same silhouette, so one of them is enough.
#pragma once
#include <array>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "voxray/appearance/layout.h"
#include "voxray/appearance/sampling_rays.hpp"
#include "voxray/appearance/voxel_sampler.hpp"

namespace voxray::appearance {

using directional_opacities = std::array<double, VX_APP_DIRECTIONS>;

inline glm::dvec3 opacity_direction(unsigned k) {
    return glm::normalize(glm::dvec3(VX_APP_DIR(k, 0u), VX_APP_DIR(k, 1u), VX_APP_DIR(k, 2u)));
}

// Ray ids of the opacity rays in the random streams, apart from the sampling rays'.
inline constexpr std::uint32_t opacity_ray_ids = 0x80000000u;

template <class Surfaces>
directional_opacities directional_opacity(const Surfaces& surfaces, glm::ivec3 voxel, unsigned strata,
                                          std::uint64_t seed) {
    directional_opacities alpha{};
    const voxel_stream stream(seed, voxel);
    for (unsigned k = 0; k < VX_APP_DIRECTIONS; ++k) {
        glm::dvec3 d = opacity_direction(k);
        unsigned rays = 0;
        double covered = 0;
        for (int axis = 0; axis < 3; ++axis) {
            if (VX_APP_DIR(k, unsigned(axis)) == 0.0f) continue;
            int u = (axis + 1) % 3, v = (axis + 2) % 3;
            for (unsigned cell = 0; cell < strata * strata; ++cell, ++rays) {
                std::uint32_t id = opacity_ray_ids + (k * 3u + unsigned(axis)) * strata * strata + cell;
                glm::dvec3 p(0.0);
                p[axis] = d[axis] > 0 ? 0.0 : 1.0;
                p[u] = (double(cell % strata) + stream.uniform01(id, 0)) / double(strata);
                p[v] = (double(cell / strata) + stream.uniform01(id, 1)) / double(strata);
                covered += surfaces.coverage(glm::dvec3(voxel) + p, d, exit_length(p, d));
            }
        }
        alpha[k] = covered / double(rays);
    }
    return alpha;
}

}  // namespace voxray::appearance
