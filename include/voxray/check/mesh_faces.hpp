// The canonical face set of a chunk, two ways: by brute force (every solid voxel, every side
// whose neighbour is empty: one unit face with its material and AO) and by expanding a
// mesh's quads into the unit faces they cover. A correct mesh gives the same sorted list;
// a quad that overlaps another gives a duplicate and so a difference. Also checks that the
// buffer is in POP order and that the table matches it.
#pragma once
#include <algorithm>
#include <cstdint>
#include <string>
#include <vector>

#include "voxray/meshing/chunk.hpp"
#include "voxray/meshing/chunk_mesh.hpp"
#include "voxray/meshing/face_ao.hpp"
#include "voxray/meshing/mesher.hpp"

namespace voxray::check {

// A unit face as one sortable number: voxel index (18 bits), face (3), material (16), AO (8).
inline std::uint64_t unit_face_key(glm::ivec3 p, int face, int material, int ao) {
    return std::uint64_t(meshing::chunk_voxels::voxel_index(p.x, p.y, p.z)) | (std::uint64_t(face) << 18) |
           (std::uint64_t(material) << 21) | (std::uint64_t(ao) << 37);
}

inline std::vector<std::uint64_t> brute_force_faces(const meshing::chunk_voxels& c, bool ambient_occlusion) {
    static constexpr int step[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
    std::vector<std::uint64_t> faces;
    const int n = meshing::chunk_edge;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) {
                int material = c.material_at(x, y, z);
                if (!material) continue;
                for (int f = 0; f < 6; ++f) {
                    if (c.solid(x + step[f][0], y + step[f][1], z + step[f][2])) continue;
                    int ao = ambient_occlusion ? int(meshing::face_ao(c, {x, y, z}, f)) : VX_MESH_AO_OPEN;
                    faces.push_back(unit_face_key({x, y, z}, f, material, ao));
                }
            }
    std::sort(faces.begin(), faces.end());
    return faces;
}

inline std::vector<std::uint64_t> expand_quads(const meshing::chunk_mesh& m) {
    std::vector<std::uint64_t> faces;
    for (std::uint32_t i = 0; i < m.quad_count(); ++i) {
        meshing::quad q = m.at(i);
        int u = int(VX_MESH_U_AXIS(q.face)), v = int(VX_MESH_V_AXIS(q.face));
        for (int dv = 0; dv < q.h; ++dv)
            for (int du = 0; du < q.w; ++du) {
                glm::ivec3 p = q.voxel;
                p[u] += du, p[v] += dv;
                faces.push_back(unit_face_key(p, q.face, q.material, q.ao));
            }
    }
    std::sort(faces.begin(), faces.end());
    return faces;
}

// Faces in one list and not the other (each duplicate counts).
inline std::uint64_t face_set_mismatches(const std::vector<std::uint64_t>& a, const std::vector<std::uint64_t>& b) {
    std::vector<std::uint64_t> diff;
    std::set_symmetric_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(diff));
    return diff.size();
}

// "" when the quads are face-major, coarse to fine within a face, every level is the one
// meshing::quad_level gives (at most that once squashed faces were removed: `exact` false),
// no quad leaves the chunk, and the table gives each prefix; else what is wrong, for the
// first quad or entry found.
inline std::string pop_order_problem(const meshing::chunk_mesh& m, bool exact = true) {
    for (int f = 0; f < VX_MESH_FACES; ++f) {
        std::uint32_t begin = m.face_begin(f), end = m.face_end(f, 0);
        if (begin > end || end > m.quad_count()) return "face " + std::to_string(f) + ": table range out of order";
        for (std::uint32_t i = begin; i < end; ++i) {
            meshing::quad q = m.at(i);
            int u = int(VX_MESH_U_AXIS(q.face)), v = int(VX_MESH_V_AXIS(q.face));
            if (q.face != f) return "quad " + std::to_string(i) + " has face " + std::to_string(q.face) + " in face " + std::to_string(f) + "'s range";
            if (q.voxel[u] + q.w > meshing::chunk_edge || q.voxel[v] + q.h > meshing::chunk_edge)
                return "quad " + std::to_string(i) + " leaves the chunk";
            int computed = meshing::quad_level(q.voxel[u], q.w, q.voxel[v], q.h);
            if (q.level < 1 || q.level > computed || (exact && q.level != computed))
                return "quad " + std::to_string(i) + " has level " + std::to_string(q.level) + ", not " +
                       std::to_string(computed);
            if (i > begin && m.at(i - 1).level < q.level) return "quad " + std::to_string(i) + " is coarser than the one before it";
            for (int lod = 0; lod < VX_MESH_LEVELS; ++lod) {
                bool drawn = i < m.face_end(f, lod);
                if (drawn != (q.level > lod))
                    return "quad " + std::to_string(i) + " of level " + std::to_string(q.level) + (drawn ? " is" : " is not") +
                           " in the prefix of level of detail " + std::to_string(lod);
            }
        }
    }
    if (m.face_end(VX_MESH_FACES - 1, 0) != m.quad_count()) return "the table does not end at the last quad";
    return "";
}

}  // namespace voxray::check
