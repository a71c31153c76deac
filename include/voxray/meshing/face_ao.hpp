// Ambient occlusion of a unit face, the usual four-corner rule: at each corner, the two
// voxels beside it and the one diagonal to it in the layer in front of the face; two solid
// sides close the corner (0), else 3 minus the solid count. Corners in layout.h's order.
#pragma once
#include <cstdint>

#include <glm/vec3.hpp>

#include "voxray/meshing/chunk.hpp"
#include "voxray/meshing/layout.h"

namespace voxray::meshing {

// Corner c's steps along u and v (layout.h's corner order).
inline constexpr int ao_corner_du[4] = {-1, 1, 1, -1}, ao_corner_dv[4] = {-1, -1, 1, 1};

// One corner's AO from its two side voxels and its diagonal one (each 0 or 1).
inline std::uint32_t corner_ao(int side_u, int side_v, int diagonal) {
    return std::uint32_t(side_u && side_v ? 0 : 3 - (side_u + side_v + diagonal));
}

// 4 x 2 bits, corner c at bits 2c; p is the face's voxel (chunk-local, 0..63).
inline std::uint32_t face_ao(const chunk_voxels& c, glm::ivec3 p, int face) {
    const int n = int(VX_MESH_NORMAL_AXIS(face)), u = int(VX_MESH_U_AXIS(face)), v = int(VX_MESH_V_AXIS(face));
    glm::ivec3 front = p;
    front[n] += VX_MESH_POSITIVE(face) ? 1 : -1;
    auto solid = [&](int du, int dv) {
        glm::ivec3 q = front;
        q[u] += du, q[v] += dv;
        return int(c.solid(q.x, q.y, q.z));
    };
    std::uint32_t bits = 0;
    for (int corner = 0; corner < 4; ++corner) {
        int du = ao_corner_du[corner], dv = ao_corner_dv[corner];
        int side_u = solid(du, 0), side_v = solid(0, dv), diagonal = solid(du, dv);
        bits |= corner_ao(side_u, side_v, diagonal) << (2 * corner);
    }
    return bits;
}

}  // namespace voxray::meshing
