// The colour a triangle gives a voxel it covers: the surface (io/mesh_surface.hpp) sampled
// at the points of the triangle nearest to nine points of the voxel (its centre and the
// centres of its eight octants), averaged in linear RGB over the samples the alpha rule
// keeps. None kept: the triangle does not claim the voxel (a leaf card's transparent part).
#pragma once
#include <cstdint>
#include <optional>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "voxray/io/mesh_surface.hpp"
#include "voxray/model/palette.hpp"

namespace voxray::io {

// Barycentric weights (of a, b, c) of the point of triangle abc nearest to p, by the
// Voronoi regions of its corners and edges; a degenerate triangle gives a point on it too.
inline glm::dvec3 nearest_barycentric(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c, glm::dvec3 p) {
    glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
    glm::dvec3 bp = p - b;
    double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
    double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0 && d1 - d3 > 0) {
        double v = d1 / (d1 - d3);
        return {1 - v, v, 0};
    }
    glm::dvec3 cp = p - c;
    double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
    double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0 && d2 - d6 > 0) {
        double w = d2 / (d2 - d6);
        return {1 - w, 0, w};
    }
    double va = d3 * d6 - d5 * d4;
    if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0 && (d4 - d3) + (d5 - d6) > 0) {
        double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return {0, 1 - w, w};
    }
    double sum = va + vb + vc;
    if (!(sum > 0)) return {1, 0, 0};  // degenerate: the regions above missed by rounding
    double v = vb / sum, w = vc / sum;
    return {1 - v - w, v, w};
}

// Linear RGB to 8-bit sRGB by the exact sRGB curve (data; rays/shading.hpp's to_srgb8 is a
// display gamma for pictures).
inline rgba encode_srgb8(glm::vec4 linear) {
    auto byte = [](float c) { return std::uint8_t(linear_to_srgb(c) * 255.0f + 0.5f); };
    return {byte(linear.r), byte(linear.g), byte(linear.b), 255};
}

// The colour triangle t (corners `v` in voxel coordinates) gives voxel `cell`, or none.
inline std::optional<rgba> voxel_colour(const mesh_surface& s, std::size_t t, const glm::dvec3 v[3], glm::ivec3 cell) {
    const mesh_material& m = s.materials[s.triangle_materials[t]];
    if (!s.varies(t)) {
        if (m.cuts() && m.base_colour.a < m.cutoff()) return std::nullopt;
        return encode_srgb8(m.base_colour);
    }
    glm::dvec3 centre = glm::dvec3(cell) + 0.5;
    glm::vec4 sum(0.0f);
    int kept = 0;
    for (int k = 0; k < 9; ++k) {
        glm::dvec3 p = centre;
        if (k > 0) p += glm::dvec3((k - 1) & 1 ? 0.25 : -0.25, (k - 1) & 2 ? 0.25 : -0.25, (k - 1) & 4 ? 0.25 : -0.25);
        glm::vec4 c = s.colour_at(t, nearest_barycentric(v[0], v[1], v[2], p));
        if (m.cuts() && c.a < m.cutoff()) continue;
        sum += c;
        ++kept;
    }
    if (!kept) return std::nullopt;
    return encode_srgb8(sum / float(kept));
}

}  // namespace voxray::io
