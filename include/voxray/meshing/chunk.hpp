// What the mesher reads: one 64^3 chunk of materials and whether each voxel of the one-voxel
// shell around it is solid (the neighbours' border slices, edges and corners included:
// faces on the chunk's sides need the next voxel, ambient occlusion the diagonal ones).
//
// Occupancy is kept as 64-bit rows along x, the mesher's unit of work:
//
//   rows[(z + 1) * 66 + (y + 1)]  bit x = voxel (x, y, z) is solid, x in 0..63,
//                                 y and z in -1..64 (the shell's rows included)
//   x_lo / x_hi  [same index]     voxel (-1, y, z) / (64, y, z) is solid (the x shell)
#pragma once
#include <bit>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "voxray/core/error.hpp"
#include "voxray/meshing/layout.h"
#include "voxray/meshing/occupancy.hpp"

namespace voxray::meshing {

inline constexpr int chunk_edge = VX_MESH_CHUNK_EDGE;
inline constexpr int padded_edge = chunk_edge + 2;

struct chunk_voxels {
    glm::ivec3 origin{0};                 // world coordinates of local voxel (0, 0, 0)
    std::vector<std::uint8_t> material;   // 64^3 bytes, x fastest, then y, then z; 0 = empty
    std::vector<std::uint64_t> rows;      // 66 * 66 rows, see above
    std::vector<std::uint8_t> x_lo, x_hi; // 66 * 66 each

    chunk_voxels()
        : material(std::size_t(chunk_edge) * chunk_edge * chunk_edge, 0),
          rows(padded_edge * padded_edge, 0),
          x_lo(padded_edge * padded_edge, 0),
          x_hi(padded_edge * padded_edge, 0) {}

    static int row_index(int y, int z) { return (z + 1) * padded_edge + (y + 1); }
    static std::size_t voxel_index(int x, int y, int z) {
        return std::size_t(x) + std::size_t(chunk_edge) * (std::size_t(y) + std::size_t(chunk_edge) * std::size_t(z));
    }

    std::uint8_t material_at(int x, int y, int z) const { return material[voxel_index(x, y, z)]; }

    // Solid test anywhere in the padded box, x, y, z in -1..64.
    bool solid(int x, int y, int z) const {
        int r = row_index(y, z);
        if (x < 0) return x_lo[r] != 0;
        if (x >= chunk_edge) return x_hi[r] != 0;
        return (rows[r] >> x) & 1u;
    }

    // Marks a shell voxel (at least one coordinate -1 or 64) solid or empty.
    void set_shell(int x, int y, int z, bool is_solid) {
        int r = row_index(y, z);
        if (x < 0) x_lo[r] = is_solid;
        else if (x >= chunk_edge) x_hi[r] = is_solid;
        else if (is_solid) rows[r] |= std::uint64_t(1) << x;
        else rows[r] &= ~(std::uint64_t(1) << x);
    }

    // Recomputes the interior rows from `material` (the shell stays as it is).
    void update_interior_rows() {
        for (int z = 0; z < chunk_edge; ++z)
            occupancy_rows(material.data() + voxel_index(0, 0, z), chunk_edge, rows.data() + row_index(0, z));
    }
};

// The chunk whose 64^3 box holds world voxel p (floor division, negative coordinates too).
inline glm::ivec3 chunk_of(glm::ivec3 p) { return p >> VX_MESH_CHUNK_BITS; }
inline glm::ivec3 chunk_origin(glm::ivec3 chunk) { return chunk * chunk_edge; }

}  // namespace voxray::meshing
