// The dense grid as a chunk source for the mesher (meshing/chunk_source.hpp): the materials
// of a box of voxels, read through the grid's own layout (dense_grid/layout.h) from its blob,
// so what is meshed is what is traced. A row of up to 16 voxels inside one 16^3 chunk costs
// one table lookup; empty chunks and voxels outside the grid read as 0.
#pragma once
#include <algorithm>
#include <cstdint>

#include "voxray/core/box.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/dense_grid/layout.h"

namespace voxray {

inline void read_box(const dense_grid& grid, const box3i& box, std::uint8_t* out) {
    std::fill(out, out + box.volume(), std::uint8_t(0));
    const std::uint32_t* w = grid.blob().data();
    glm::ivec3 origin, extent;
    for (int a = 0; a < 3; ++a) {
        origin[a] = std::int32_t(w[VX_DG_HEADER_ORIGIN + a]);
        extent[a] = std::int32_t(w[VX_DG_HEADER_EXTENT + a]);
    }
    const std::uint64_t chunks_x = w[VX_DG_HEADER_CHUNKS], chunks_xy = chunks_x * w[VX_DG_HEADER_CHUNKS + 1];
    const std::uint32_t* table = w + w[VX_DG_HEADER_TABLE];
    const std::uint32_t* data = w + w[VX_DG_HEADER_DATA];
    glm::ivec3 lo = glm::max(box.min, origin), hi = glm::min(box.max, origin + extent);
    glm::ivec3 e = box.extent();
    for (int z = lo.z; z < hi.z; ++z)
        for (int y = lo.y; y < hi.y; ++y)
            for (int x = lo.x; x < hi.x;) {
                glm::uvec3 q(glm::ivec3(x, y, z) - origin);
                int row_end = std::min(hi.x, x + VX_DG_CHUNK_EDGE - int(q.x & VX_DG_CHUNK_MASK));
                std::uint32_t entry = table[VX_DG_CHUNK_SLOT(std::uint64_t(q.x), q.y, q.z, chunks_x, chunks_xy)];
                if (entry != VX_DG_EMPTY_CHUNK) {
                    const std::uint32_t* record = data + std::uint64_t(entry) * VX_DG_CHUNK_WORDS;
                    std::uint8_t* dst = out + (std::size_t(z - box.min.z) * e.y + std::size_t(y - box.min.y)) * e.x;
                    for (int xx = x; xx < row_end; ++xx) {
                        std::uint32_t local = VX_DG_LOCAL(std::uint32_t(xx - origin.x), q.y, q.z);
                        dst[xx - box.min.x] = std::uint8_t(record[VX_DG_MATERIAL_WORD(local)] >> VX_DG_MATERIAL_SHIFT(local));
                    }
                }
                x = row_end;
            }
}

}  // namespace voxray
