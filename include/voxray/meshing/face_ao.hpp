// Ambient occlusion of a unit face, the usual four-corner rule: at each corner, the two
// voxels beside it and the one diagonal to it in the layer in front of the face; two solid
// sides close the corner (0), else 3 minus the solid count. Corners in layout.h's order.
#pragma once
#include <cstdint>

#include <glm/vec3.hpp>

#include "voxray/meshing/chunk.hpp"
#include "voxray/meshing/layout.h"

namespace voxray::meshing {

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
    static constexpr int corner_du[4] = {-1, 1, 1, -1}, corner_dv[4] = {-1, -1, 1, 1};
    std::uint32_t bits = 0;
    for (int corner = 0; corner < 4; ++corner) {
        int du = corner_du[corner], dv = corner_dv[corner];
        int side_u = solid(du, 0), side_v = solid(0, dv), diagonal = solid(du, dv);
        int ao = side_u && side_v ? 0 : 3 - (side_u + side_v + diagonal);
        bits |= std::uint32_t(ao) << (2 * corner);
    }
    return bits;
}

}  // namespace voxray::meshing
