// Which faces of each solid voxel touch empty space. Both Embree baselines are built from
// this: the quad scene emits one quad per exposed face, the box scene gives Embree only
// voxels with at least one exposed face (a ray that starts outside the solid can hit no
// other) and keeps the fully enclosed ones for a point lookup of inside starts.
#pragma once
#include <cstdint>

#include <glm/vec3.hpp>

#include "voxray/model/voxel_model.hpp"

namespace voxray::embree {

// Bit f of an exposure mask is set when face f (VX_FACE_* numbering: axis * 2 + negative)
// borders an empty voxel.
inline constexpr std::uint8_t all_faces_exposed = 0x3F;

// Outward step of face f: +x, -x, +y, -y, +z, -z.
inline glm::ivec3 face_step(int f) {
    glm::ivec3 s(0);
    s[f >> 1] = (f & 1) ? -1 : 1;
    return s;
}

// Calls f(position, material, exposed_mask) for every solid voxel of the model, chunk by
// chunk. Neighbours inside the same 16^3 chunk are read from the chunk directly; only the
// chunk's border voxels pay for a hash lookup in the model, so this costs little more than
// for_each_voxel.
template <class F>
void for_each_voxel_exposure(const voxel_model& model, F&& f) {
    constexpr int edge = voxel_model::chunk_edge;
    model.for_each_chunk([&](glm::ivec3 origin, const voxel_model::chunk& c) {
        for (int i = 0; i < voxel_model::chunk_voxels; ++i) {
            std::uint8_t value = c.voxels[i];
            if (!value) continue;
            glm::ivec3 local = voxel_model::local_position(i);
            std::uint8_t mask = 0;
            for (int face = 0; face < 6; ++face) {
                glm::ivec3 n = local + face_step(face);
                bool in_chunk = n.x >= 0 && n.y >= 0 && n.z >= 0 && n.x < edge && n.y < edge && n.z < edge;
                std::uint8_t neighbour = in_chunk ? c.voxels[voxel_model::local_index(n)] : model.get(origin + n);
                if (!neighbour) mask |= std::uint8_t(1u << face);
            }
            f(origin + local, value, mask);
        }
    });
}

}  // namespace voxray::embree
