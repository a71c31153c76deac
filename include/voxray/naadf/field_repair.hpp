// Keeping the AADFs of pages and chunks right while the world is edited (paper section
// 3.5). A chunk edit recomputes the voxel and block fields inside that chunk at once
// (they depend only on it). A chunk or page that turns non-empty can break the cuboid
// of an empty neighbour in the same page (or the page table): reset_broken_fields sets
// exactly those fields to 0, which is always correct, before any ray sees the edit.
// regrow_fields later grows fields back to full size: naadf::refine runs it page by page
// within a budget, on just the cells an edit can have changed (page_cells):
//   - cells whose field was reset, and chunks that turned empty (they have none yet);
//   - empty cells whose cuboid grown by one cell meets a chunk that turned empty: growth
//     only ever tests slabs inside that box, so every other cell's cuboid is the same
//     as a full rebuild would give (a chunk that filled only makes failed tests fail).
// So a refined page equals a freshly built one, at the cost of the cells that changed.
#pragma once
#include <algorithm>
#include <bitset>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "voxray/naadf/aadf.hpp"
#include "voxray/naadf/layout.h"

namespace voxray::naadf_detail {

// One flag per chunk of a page.
using page_cells = std::bitset<VX_NA_CHUNK_ARRAY_WORDS>;

// The cuboid of empty cell (x, y, z) whose field is c, in cells; `grow` cells wider
// every way.
inline void field_box(std::uint32_t c, int x, int y, int z, unsigned k, int grow, int lo[3], int hi[3]) {
    lo[0] = x - int(VX_NA_AADF_FIELD(c, 1u, k)) - grow, hi[0] = x + 1 + int(VX_NA_AADF_FIELD(c, 0u, k)) + grow;
    lo[1] = y - int(VX_NA_AADF_FIELD(c, 3u, k)) - grow, hi[1] = y + 1 + int(VX_NA_AADF_FIELD(c, 2u, k)) + grow;
    lo[2] = z - int(VX_NA_AADF_FIELD(c, 5u, k)) - grow, hi[2] = z + 1 + int(VX_NA_AADF_FIELD(c, 4u, k)) + grow;
}

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
                int lo[3], hi[3];
                field_box(c, x, y, z, k, 0, lo, hi);
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

// The empty chunks of a page whose field may grow now that the chunks in `emptied`
// turned empty: those whose cuboid grown by one chunk meets one of them.
inline page_cells near_emptied(const std::uint32_t* cells, const page_cells& emptied) {
    const glm::ivec3 n(16);
    std::vector<std::uint8_t> flags(VX_NA_CHUNK_ARRAY_WORDS);
    for (std::size_t i = 0; i < flags.size(); ++i) flags[i] = emptied[i];
    box_counts counts(n, flags);
    page_cells out;
    for (int i = 0; i < VX_NA_CHUNK_ARRAY_WORDS; ++i) {
        if (VX_NA_STATE(cells[i]) != VX_NA_EMPTY) continue;
        int lo[3], hi[3];
        field_box(cells[i], i & 15, i >> 4 & 15, i >> 8, VX_NA_CHUNK_AADF_BITS, 1, lo, hi);
        for (int a = 0; a < 3; ++a) lo[a] = std::max(lo[a], 0), hi[a] = std::min(hi[a], 16);
        if (!counts.empty(lo, hi)) out.set(std::size_t(i));
    }
    return out;
}

// Grows the fields of the chunks of a page flagged in `which` (the empty ones) to full
// size; calls changed(i) for each word that changed.
template <class Changed>
void regrow_page_fields(std::uint32_t* cells, const page_cells& which, Changed&& changed) {
    const glm::ivec3 n(16);
    auto solid = solid_cells(cells, VX_NA_CHUNK_ARRAY_WORDS);
    box_counts counts(n, solid);
    auto box_empty = [&](const int* lo, const int* hi) { return counts.empty(lo, hi); };
    for (int i = 0; i < VX_NA_CHUNK_ARRAY_WORDS; ++i) {
        if (!which[std::size_t(i)] || solid[i]) continue;
        std::uint32_t field = pack_aadf(grow_cuboid({i & 15, i >> 4 & 15, i >> 8}, n, 15, box_empty), VX_NA_CHUNK_AADF_BITS);
        if (cells[i] == field) continue;
        cells[i] = field;
        changed(std::size_t(i));
    }
}

}  // namespace voxray::naadf_detail
