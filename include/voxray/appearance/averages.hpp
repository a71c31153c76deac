// The *averages* record (appearance/layout.h) of one voxel from its samples
// (appearance/voxel_sampler.hpp): the mean colour (linear, stored sRGB), the mean normal
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
#include "voxray/appearance/voxel_sampler.hpp"
#include "voxray/io/surface_sample.hpp"

namespace voxray::appearance {

// Octahedral mapping of a unit vector to [-1, 1]^2 and back.
inline glm::vec2 octahedral(glm::vec3 n) {
    n /= std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z);
    if (n.z >= 0) return {n.x, n.y};
    return {(1.0f - std::fabs(n.y)) * (n.x >= 0 ? 1.0f : -1.0f), (1.0f - std::fabs(n.x)) * (n.y >= 0 ? 1.0f : -1.0f)};
}
inline glm::vec3 from_octahedral(glm::vec2 e) {
    glm::vec3 n(e.x, e.y, 1.0f - std::fabs(e.x) - std::fabs(e.y));
    if (n.z < 0) {
        float x = n.x;
        n.x = (1.0f - std::fabs(n.y)) * (x >= 0 ? 1.0f : -1.0f);
        n.y = (1.0f - std::fabs(x)) * (n.y >= 0 ? 1.0f : -1.0f);
    }
    return glm::normalize(n);
}

inline std::uint32_t snorm16(float x) {
    return std::uint32_t(std::uint16_t(std::int16_t(std::lround(std::clamp(x, -1.0f, 1.0f) * 32767.0f))));
}
inline float from_snorm16(std::uint32_t v) { return std::max(float(std::int16_t(std::uint16_t(v))) / 32767.0f, -1.0f); }

inline std::array<std::uint32_t, VX_APP_AVERAGES_WORDS> averages_record(const voxel_samples& v) {
    std::uint32_t opacity = v.rays ? std::uint32_t(std::lround(255.0 * double(v.hits) / double(v.rays))) : 0u;
    if (v.seen.empty()) return {VX_APP_AVG_WORD0(0u, 0u, 0u, opacity), 0u};
    glm::vec4 colour(0.0f);
    glm::vec3 normal(0.0f);
    for (const surface_sample& s : v.seen) colour += s.colour, normal += s.normal;
    rgba c = io::encode_srgb8(colour / float(v.seen.size()));
    float length = glm::length(normal);
    glm::vec2 e = length > 1e-6f ? octahedral(normal / length) : glm::vec2(0.0f);
    return {VX_APP_AVG_WORD0(std::uint32_t(c.r), std::uint32_t(c.g), std::uint32_t(c.b), opacity),
            VX_APP_AVG_WORD1(snorm16(e.x), snorm16(e.y))};
}

}  // namespace voxray::appearance
