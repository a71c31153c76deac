// The simple shading of `voxray render` and examples/render_vox.cpp: palette colour lit by
// one directional sun (Lambert plus ambient, black where a shadow ray hit), a sky
// gradient on a miss, and gamma-encoded 8-bit output.
//
//   glm::vec3 sun = voxray::sun_direction(model.up_axis);
//   glm::vec3 c = hits[i].is_hit() ? voxray::shade(model.palette(), hits[i], sun, shadow_hits[i].is_hit())
//                                  : voxray::sky(rays[i].direction, model.up_axis);
//   std::array<std::uint8_t, 3> rgb = voxray::to_srgb8(c);
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>

#include <glm/common.hpp>
#include <glm/geometric.hpp>

#include "voxray/core/hit.hpp"
#include "voxray/model/palette.hpp"

namespace voxray {

// A sun above and to the side, whatever the scene's up axis (1: Y-up, 2: Z-up).
inline glm::vec3 sun_direction(int up_axis) {
    glm::vec3 l(0.0f);
    l[up_axis] = 0.8f;
    l[(up_axis + 1) % 3] = 0.45f;
    l[(up_axis + 2) % 3] = 0.35f;
    return glm::normalize(l);
}

// The hit voxel's palette colour, linear in [0, 1].
inline glm::vec3 albedo(const palette& p, const hit& h) {
    rgba c = p[std::uint8_t(h.material)].colour;
    return glm::vec3(c.r, c.g, c.b) / 255.0f;
}

// The colour of a hit whose material is an RGBA8 colour (r | g<<8 | b<<16 | a<<24), as
// the sparse voxel DAG's colour blocks give, linear in [0, 1].
inline glm::vec3 albedo_rgba8(const hit& h) {
    return glm::vec3(h.material & 255u, (h.material >> 8) & 255u, (h.material >> 16) & 255u) / 255.0f;
}

// Lambert with 30% ambient; `in_shadow`: the shadow ray towards `to_sun` hit something.
inline glm::vec3 shade(glm::vec3 albedo, const hit& h, glm::vec3 to_sun, bool in_shadow) {
    float lambert = std::max(0.0f, glm::dot(face_normal(h.normal), to_sun));
    return albedo * (0.3f + 0.7f * (in_shadow ? 0.0f : lambert));
}
inline glm::vec3 shade(const palette& p, const hit& h, glm::vec3 to_sun, bool in_shadow) {
    return shade(albedo(p, h), h, to_sun, in_shadow);
}

// Pale at the horizon, blue overhead.
inline glm::vec3 sky(glm::vec3 direction, int up_axis) {
    float up = std::clamp(direction[up_axis] * 0.5f + 0.5f, 0.0f, 1.0f);
    return glm::mix(glm::vec3(0.85f, 0.88f, 0.92f), glm::vec3(0.45f, 0.62f, 0.86f), up);
}

// Linear colour to 8-bit sRGB-like values (gamma 2.2).
inline std::array<std::uint8_t, 3> to_srgb8(glm::vec3 c) {
    std::array<std::uint8_t, 3> out;
    for (int k = 0; k < 3; ++k) out[k] = std::uint8_t(std::clamp(std::pow(c[k], 1.0f / 2.2f), 0.0f, 1.0f) * 255.0f + 0.5f);
    return out;
}

}  // namespace voxray
