// Keeping the AADFs of pages and chunks right while the world is edited (paper section
// 3.5). A chunk edit recomputes the voxel and block fields inside that chunk at once
// (they depend only on it). A chunk or page that turns non-empty can break the cuboid
// of an empty neighbour in the same page (or the page table): reset_broken_fields sets
// exactly those fields to 0, which is always correct, before any ray sees the edit.
// regrow_fields later grows every field of the grid back to full size: naadf::refine
// runs it page by page within a budget.
#pragma once
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "voxray/naadf/aadf.hpp"
#include "voxray/naadf/layout.h"

namespace voxray::naadf_detail {

// Whether each cell of a grid (x fastest) is non-empty.
inline std::vector<std::uint8_t> solid_cells(const std::uint32_t* cells, std::size_t count) {
    std::vector<std::uint8_t> solid(count);
    for (std::size_t i = 0; i < count; ++i) solid[i] = VX_NA_STATE(cells[i]) != VX_NA_EMPTY;
    return solid;
}

// Sets to 0 the field of every empty cell of grid `n` whose cuboid holds a non-empty
// cell (or leaves the grid); calls changed(i) for each. Fields have k bits a direction.
template <class Changed>
void reset_broken_fields(std::uint32_t* cells, glm::ivec3 n, unsigned k, Changed&& changed) {
    std::size_t count = std::size_t(n.x) * n.y * n.z;
    box_counts counts(n, solid_cells(cells, count));
    std::size_t i = 0;
    for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
            for (int x = 0; x < n.x; ++x, ++i) {
                std::uint32_t c = cells[i];
                if (VX_NA_STATE(c) != VX_NA_EMPTY || c == 0) continue;
                int lo[3] = {x - int(VX_NA_AADF_FIELD(c, 1u, k)), y - int(VX_NA_AADF_FIELD(c, 3u, k)), z - int(VX_NA_AADF_FIELD(c, 5u, k))};
                int hi[3] = {x + 1 + int(VX_NA_AADF_FIELD(c, 0u, k)), y + 1 + int(VX_NA_AADF_FIELD(c, 2u, k)), z + 1 + int(VX_NA_AADF_FIELD(c, 4u, k))};
                bool inside = lo[0] >= 0 && lo[1] >= 0 && lo[2] >= 0 && hi[0] <= n.x && hi[1] <= n.y && hi[2] <= n.z;
                if (inside && counts.empty(lo, hi)) continue;
                cells[i] = 0;
                changed(i);
            }
}

// Grows the field of every empty cell of grid `n` to its full size (at most `limit`
// cells a direction); calls changed(i) for each cell whose word changed.
template <class Changed>
void regrow_fields(std::uint32_t* cells, glm::ivec3 n, unsigned limit, unsigned k, Changed&& changed) {
    std::size_t count = std::size_t(n.x) * n.y * n.z;
    auto solid = solid_cells(cells, count);
    auto fields = grid_aadfs(n, solid, limit, k);
    for (std::size_t i = 0; i < count; ++i)
        if (!solid[i] && cells[i] != fields[i]) {
            cells[i] = fields[i];
            changed(i);
        }
}

}  // namespace voxray::naadf_detail
