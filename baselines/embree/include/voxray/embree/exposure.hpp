// Which faces of each solid voxel touch empty space. Both Embree baselines are built from
// this: the quad scene emits one quad per exposed face; the box scene gives Embree only the
// voxels that touch empty space at all, through a face, an edge or a corner (see
// box_scene.hpp for why edges and corners count).
#pragma once
#include <cstdint>

#include <glm/vec3.hpp>

#include "voxray/model/voxel_model.hpp"

namespace voxray::embree {

// Bit f of an exposure mask is set when face f (VX_FACE_* numbering: axis * 2 + negative)
// borders an empty voxel.
inline constexpr std::uint8_t all_faces_exposed = 0x3F;
// Bit 6, reported only when asked for and no face is exposed: some edge or corner
// neighbour (one of the other 20 of the 26) is empty.
inline constexpr std::uint8_t diagonal_exposed = 0x40;

// Outward step of face f: +x, -x, +y, -y, +z, -z.
inline glm::ivec3 face_step(int f) {
    glm::ivec3 s(0);
    s[f >> 1] = (f & 1) ? -1 : 1;
    return s;
}

// Calls f(position, material, exposed_mask) for every solid voxel of the model, chunk by
// chunk. Neighbours inside the same 16^3 chunk are read from the chunk directly; only the
// chunk's border voxels pay for a hash lookup in the model, so this costs little more than
// for_each_voxel. With `diagonals`, voxels with no exposed face also get diagonal_exposed
// when an edge or corner neighbour is empty.
template <class F>
void for_each_voxel_exposure(const voxel_model& model, F&& f, bool diagonals = false) {
    constexpr int edge = voxel_model::chunk_edge;
    model.for_each_chunk([&](glm::ivec3 origin, const voxel_model::chunk& c) {
        auto empty = [&](glm::ivec3 n) {
            bool in_chunk = n.x >= 0 && n.y >= 0 && n.z >= 0 && n.x < edge && n.y < edge && n.z < edge;
            return (in_chunk ? c.voxels[voxel_model::local_index(n)] : model.get(origin + n)) == 0;
        };
        for (int i = 0; i < voxel_model::chunk_voxels; ++i) {
            std::uint8_t value = c.voxels[i];
            if (!value) continue;
            glm::ivec3 local = voxel_model::local_position(i);
            std::uint8_t mask = 0;
            for (int face = 0; face < 6; ++face)
                if (empty(local + face_step(face))) mask |= std::uint8_t(1u << face);
            if (diagonals && !mask) {
                for (int k = 0; k < 27 && !mask; ++k) {
                    glm::ivec3 s(k % 3 - 1, k / 3 % 3 - 1, k / 9 - 1);
                    int nonzero = (s.x != 0) + (s.y != 0) + (s.z != 0);
                    if (nonzero >= 2 && empty(local + s)) mask = diagonal_exposed;
                }
            }
            f(origin + local, value, mask);
        }
    });
}

}  // namespace voxray::embree
