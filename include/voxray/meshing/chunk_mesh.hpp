// A meshed chunk: its quads in POP order and the table of prefixes (meshing/layout.h), with
// the questions an engine asks of it: where face f starts, how many quads to draw at a
// level of detail, and each quad's fields.
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "voxray/meshing/layout.h"

namespace voxray::meshing {

// One quad's fields, unpacked (tests, exporters, statistics).
struct quad {
    glm::ivec3 voxel{0};  // chunk-local first voxel
    int w = 1, h = 1;     // extents along the face's u and v axes
    int face = 0;         // VX_FACE_*
    int material = 0;
    int ao = VX_MESH_AO_OPEN;  // 4 x 2 bits, corner c at bits 2c
    int level = 1;             // levels of detail it survives

    static quad unpack(std::uint32_t w0, std::uint32_t w1) {
        quad q;
        q.voxel = {int(VX_MESH_X(w0)), int(VX_MESH_Y(w0)), int(VX_MESH_Z(w0))};
        q.w = int(VX_MESH_W(w0)), q.h = int(VX_MESH_H(w0));
        q.face = int(VX_MESH_FACE(w1)), q.material = int(VX_MESH_MATERIAL(w1));
        q.ao = int(VX_MESH_AO_BITS(w1)), q.level = int(VX_MESH_LEVEL(w1));
        return q;
    }
};

struct chunk_mesh {
    glm::ivec3 origin{0};                 // world coordinates of the chunk's local (0, 0, 0)
    std::vector<std::uint32_t> words;     // VX_MESH_QUAD_WORDS per quad, POP order
    std::array<std::uint32_t, VX_MESH_TABLE_ENTRIES> table{};

    std::uint32_t quad_count() const { return std::uint32_t(words.size() / VX_MESH_QUAD_WORDS); }
    quad at(std::uint32_t i) const { return quad::unpack(words[2 * i], words[2 * i + 1]); }

    std::uint32_t face_begin(int face) const { return face ? table[VX_MESH_TABLE_END(face - 1, 0)] : 0u; }
    // End of face f's quads drawn at level of detail `level` (0..6): draw [face_begin, face_end).
    std::uint32_t face_end(int face, int level) const { return table[VX_MESH_TABLE_END(face, level)]; }
    std::uint32_t drawn(int face, int level) const { return face_end(face, level) - face_begin(face); }
    std::uint32_t drawn(int level) const {
        std::uint32_t n = 0;
        for (int f = 0; f < VX_MESH_FACES; ++f) n += drawn(f, level);
        return n;
    }

    std::size_t bytes() const { return words.size() * sizeof(std::uint32_t) + sizeof(table); }
};

}  // namespace voxray::meshing
