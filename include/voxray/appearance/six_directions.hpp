// The *six directions* record (appearance/layout.h): the baseline after Crassin et al.'s
// anisotropic voxels. The voxel's sampling rays are split by the axis direction they travel
// closest to; for each, the share that stopped and the mean lit colour of the surfaces they
// saw from the front (shading as in appearance/record.h). Surfaces met from behind occlude
// but add no colour: inside a closed surface's voxel, rays that start in the solid meet its
// back, which no view from outside does.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "voxray/appearance/layout.h"
#include "voxray/appearance/record_codes.hpp"
#include "voxray/appearance/voxel_sampler.hpp"

namespace voxray::appearance {

struct directional_light {
    glm::vec3 to_light{0.0f, 1.0f, 0.0f};  // unit
    float ambient = 0.2f;
};

inline float lambert_ambient(glm::vec3 n, const directional_light& l) {
    return l.ambient + (1.0f - l.ambient) * std::max(glm::dot(n, l.to_light), 0.0f);
}

// The word of the axis direction closest to travel direction d: 2 a + (1 if d_a < 0).
inline int six_direction_slot(glm::vec3 d) {
    glm::vec3 a = glm::abs(d);
    int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    return 2 * axis + (d[axis] < 0 ? 1 : 0);
}

inline std::array<std::uint32_t, VX_APP_SIX_WORDS> six_directions_record(const voxel_samples& v,
                                                                          const directional_light& light) {
    std::array<glm::dvec3, VX_APP_SIX_WORDS> lit{};
    std::array<std::uint32_t, VX_APP_SIX_WORDS> rays{}, hits{}, samples{};
    for (const ray_outcome& o : v.outcomes) {
        int slot = six_direction_slot(o.direction);
        ++rays[slot];
        if (!o.hit) continue;
        ++hits[slot];
        if (o.sample >= 0) {
            const surface_sample& s = v.seen[std::size_t(o.sample)];
            lit[slot] += glm::dvec3(glm::vec3(s.colour) * lambert_ambient(s.normal, light));
            ++samples[slot];
        }
    }
    std::array<std::uint32_t, VX_APP_SIX_WORDS> words{};
    for (int d = 0; d < VX_APP_SIX_WORDS; ++d) {
        if (!hits[d]) continue;
        glm::dvec3 c = samples[d] ? lit[d] / double(samples[d]) : glm::dvec3(0.0);  // seen only from behind
        words[d] = VX_APP_AVG_WORD0(srgb_code(c.r), srgb_code(c.g), srgb_code(c.b),
                                    unorm(double(hits[d]) / double(rays[d]), 255));
    }
    return words;
}

}  // namespace voxray::appearance
