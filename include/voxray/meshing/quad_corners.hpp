// The quads a chunk mesh draws at one level of detail as corner positions: four a quad,
// wound counter-clockwise seen from outside (as the raster path's vertex shader winds
// them), rounded to the level's grid (L_i of meshing/pop.h, without the morph). For
// exporters and for the tools that take triangles (meshoptimizer, the triangle raster path).
#pragma once
#include <array>
#include <cstdint>

#include <glm/vec3.hpp>

#include "voxray/meshing/chunk_mesh.hpp"
#include "voxray/meshing/pop.hpp"

namespace voxray::meshing {

// Calls visit(quad index, std::array<glm::ivec3, 4> corners) for each quad drawn at `level`.
template <class Visit>
void for_each_quad_at(const chunk_mesh& m, int level, Visit&& visit) {
    const int mask = ~((1 << level) - 1);
    for (int face = 0; face < VX_MESH_FACES; ++face)
        for (std::uint32_t i = m.face_begin(face); i < m.face_end(face, level); ++i) {
            std::array<glm::ivec3, 4> corners;
            for (int k = 0; k < 4; ++k) {
                // The corners run u, then v, and u x v is +normal: a negative face reversed.
                int corner = VX_MESH_POSITIVE(unsigned(face)) ? k : 3 - k;
                corners[std::size_t(k)] = quad_corner(m.words[2 * i], m.words[2 * i + 1], corner, m.origin) & mask;
            }
            visit(i, corners);
        }
}

}  // namespace voxray::meshing
