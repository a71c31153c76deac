// The *averages* record (appearance/layout.h) of one voxel from its samples
// (appearance/voxel_sampler.hpp): the mean colour (linear, stored as an sRGB code), the mean normal
// (octahedral) and the share of rays that hit, the paper's first baseline.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "voxray/appearance/layout.h"
#include "voxray/appearance/record_codes.hpp"
#include "voxray/appearance/voxel_sampler.hpp"

namespace voxray::appearance {

inline std::array<std::uint32_t, VX_APP_AVERAGES_WORDS> averages_record(const voxel_samples& v) {
    std::uint32_t opacity = v.rays ? unorm(double(v.hits) / double(v.rays), 255) : 0u;
    if (v.seen.empty()) return {VX_APP_AVG_WORD0(0u, 0u, 0u, opacity), 0u};
    glm::vec4 colour(0.0f);
    glm::vec3 normal(0.0f);
    for (const surface_sample& s : v.seen) colour += s.colour, normal += s.normal;
    colour /= float(v.seen.size());
    float length = glm::length(normal);
    glm::vec2 e = length > 1e-6f ? octahedral(normal / length) : glm::vec2(0.0f);
    return {VX_APP_AVG_WORD0(srgb_code(colour.r), srgb_code(colour.g), srgb_code(colour.b), opacity),
            VX_APP_AVG_WORD1(snorm(e.x, 16), snorm(e.y, 16))};
}

}  // namespace voxray::appearance
