// Checking a NAADF blob that came from outside (a file) before any ray or edit sees it,
// and rebuilding the host-side state around it: which arrays and groups are in use,
// each group's users, the group table. Nothing is trusted: the layout's offsets and
// sizes, every reachable cell's state and index (each chunk and block array owned by one
// cell), every type (1..255), every distance field (its cuboid must be empty and inside
// its cell above), and solid voxels only inside the world box; the voxels are counted for
// the caller to compare. A failure calls bad(word, message...) naming the blob word.
#pragma once
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "voxray/core/blob.hpp"
#include "voxray/core/box.hpp"
#include "voxray/core/error.hpp"
#include "voxray/naadf/builder.hpp"
#include "voxray/naadf/field_repair.hpp"
#include "voxray/naadf/group_table.hpp"
#include "voxray/naadf/layout.h"

namespace voxray::naadf_detail {

struct restored {
    box3i bounds;
    std::uint64_t voxels = 0;
    std::vector<std::uint8_t> chunk_live, block_live;
    group_table groups;
};

// Whether the fields of grid `n` (cells as in a chunk array) are all sound; else the
// index of the first broken one.
inline std::int64_t first_broken_field(const std::uint32_t* cells, glm::ivec3 n, unsigned k) {
    std::vector<std::uint32_t> copy(cells, cells + std::size_t(n.x) * n.y * n.z);
    std::int64_t first = -1;
    reset_broken_fields(copy.data(), n, k, [&](std::size_t i) {
        if (first < 0) first = std::int64_t(i);
    });
    return first;
}

template <class Bad>
restored restore_blob(const blob_words& w, Bad&& bad) {
    restored out;
    auto expect = [&](std::uint64_t word, std::uint64_t want, const char* what) {
        if (w[word] != want) bad(word, what, " ", w[word], " (expected ", want, ")");
    };
    expect(VX_NA_HEADER_MAGIC, VX_NA_MAGIC, "blob magic");
    expect(VX_NA_HEADER_VERSION, VX_NA_VERSION, "blob layout version");
    for (std::uint64_t r = VX_NA_HEADER_GROUPS + 1; r < VX_NA_HEADER_WORDS; ++r) expect(r, 0, "reserved header word");
    // The world box, and the grid it implies.
    for (int a = 0; a < 3; ++a) {
        auto o = std::int32_t(w[VX_NA_HEADER_ORIGIN + a]);
        std::uint32_t e = w[VX_NA_HEADER_EXTENT + a];
        if (e > std::uint32_t(std::numeric_limits<int>::max()) || std::int64_t(o) + e > std::numeric_limits<int>::max())
            bad(VX_NA_HEADER_EXTENT + a, "world extent ", e, " overflows 32-bit coordinates from origin ", o);
        out.bounds.min[a] = o;
        out.bounds.max[a] = int(std::int64_t(o) + e);
    }
    grid_placement grid = [&] {
        try {
            return grid_placement(out.bounds);
        } catch (const error& e) {
            bad(VX_NA_HEADER_EXTENT, "world extent: ", e.what());
            throw;
        }
    }();
    if (out.bounds.empty()) out.bounds = {};
    for (int a = 0; a < 3; ++a) {
        expect(VX_NA_HEADER_SHIFT + a, std::uint32_t(grid.shift[a]), "grid shift");
        expect(VX_NA_HEADER_PAGES_DIM + a, std::uint32_t(grid.pages[a]), "page table size");
    }
    // The areas: sizes from the counts, back to back, filling the blob exactly.
    std::uint64_t chunk_cap = w[VX_NA_HEADER_CHUNK_ARRAYS], block_cap = w[VX_NA_HEADER_BLOCK_ARRAYS], group_cap = w[VX_NA_HEADER_GROUPS];
    for (auto [word, cap] : {std::pair{VX_NA_HEADER_CHUNK_ARRAYS, chunk_cap}, {VX_NA_HEADER_BLOCK_ARRAYS, block_cap}, {VX_NA_HEADER_GROUPS, group_cap}})
        if (cap > VX_NA_MAX_INDEX + std::uint64_t(1)) bad(word, "array count ", cap, " above the 30-bit index limit");
    std::uint64_t table = VX_NA_HEADER_WORDS, chunks = table + grid.page_count;
    std::uint64_t blocks = chunks + chunk_cap * VX_NA_CHUNK_ARRAY_WORDS, groups = blocks + block_cap * VX_NA_BLOCK_ARRAY_WORDS;
    expect(VX_NA_HEADER_PAGE_TABLE, table, "page table offset");
    expect(VX_NA_HEADER_CHUNKS, chunks, "chunk area offset");
    expect(VX_NA_HEADER_BLOCKS, blocks, "block area offset");
    expect(VX_NA_HEADER_VOXELS, groups, "group area offset");
    if (groups + group_cap * VX_NA_GROUP_WORDS != w.size())
        bad(VX_NA_HEADER_GROUPS, "areas end at word ", groups + group_cap * VX_NA_GROUP_WORDS, " but the blob has ", w.size(), " words");

    // Cells, top down. A type is 1..255 with no other payload bits; an empty cell's
    // fields use 6 x k bits.
    auto check_cell = [&](std::uint64_t word, unsigned k, std::uint64_t cap, const char* what) {
        std::uint32_t c = w[word];
        switch (VX_NA_STATE(c)) {
        case VX_NA_EMPTY:
            if (VX_NA_PAYLOAD(c) >> (6 * k)) bad(word, what, " holds field bits beyond 6 x ", k, ": ", c);
            break;
        case VX_NA_UNIFORM:
            if ((c & ~(VX_NA_UNIFORM << 30)) == 0 || (c & ~(VX_NA_UNIFORM << 30)) > 255) bad(word, what, " has type ", c & 0x3FFFFFFFu, " outside 1..255");
            break;
        case VX_NA_MIXED:
            if (VX_NA_PAYLOAD(c) >= cap) bad(word, what, " points to array ", VX_NA_PAYLOAD(c), " of ", cap);
            break;
        default: bad(word, what, " has state 3 (undefined): ", c);
        }
    };
    auto check_fields = [&](std::uint64_t word, glm::ivec3 n, unsigned k, const char* what) {
        std::int64_t i = first_broken_field(w.data() + word, n, k);
        if (i >= 0) bad(word + std::uint64_t(i), what, " field's cuboid holds solid cells or leaves its cell: ", w[word + i]);
    };
    out.chunk_live.assign(chunk_cap, 0);
    out.block_live.assign(block_cap, 0);
    std::vector<std::uint32_t> users(group_cap, 0);
    std::uint64_t count = 0;
    const int chunk_voxels = 1 << (3 * VX_NA_CHUNK_BITS);
    // Solid content must lie inside the world: a cell of `edge` voxels at grid position g.
    auto inside_world = [&](glm::ivec3 g, int edge) {
        glm::ivec3 lo = grid.origin + g;
        return box3i{glm::max(lo, out.bounds.min), glm::min(lo + edge, out.bounds.max)}.volume() == std::uint64_t(edge) * edge * edge;
    };
    for (std::uint64_t slot = 0; slot < grid.page_count; ++slot) {
        check_cell(table + slot, VX_NA_PAGE_AADF_BITS, chunk_cap, "page cell");
        std::uint32_t page = w[table + slot];
        glm::ivec3 pg(int(slot % grid.pages.x), int(slot / grid.pages.x % grid.pages.y), int(slot / grid.pages.x / grid.pages.y));
        pg *= 1 << VX_NA_PAGE_BITS;
        if (VX_NA_STATE(page) == VX_NA_UNIFORM) {
            if (!inside_world(pg, 1 << VX_NA_PAGE_BITS)) bad(table + slot, "uniform page reaches outside the world: ", page, "");
            count += std::uint64_t(1) << (3 * VX_NA_PAGE_BITS);
        }
        if (VX_NA_STATE(page) != VX_NA_MIXED) continue;
        std::uint32_t ci = VX_NA_PAYLOAD(page);
        if (out.chunk_live[ci]++) bad(table + slot, "page cell shares chunk array ", ci, " with another page");
        std::uint64_t array = chunks + std::uint64_t(ci) * VX_NA_CHUNK_ARRAY_WORDS;
        for (std::uint32_t c = 0; c < VX_NA_CHUNK_ARRAY_WORDS; ++c) {
            check_cell(array + c, VX_NA_CHUNK_AADF_BITS, block_cap, "chunk cell");
            std::uint32_t chunk = w[array + c];
            glm::ivec3 cg = pg + glm::ivec3(int(c & 15), int(c >> 4 & 15), int(c >> 8)) * 16;
            if (VX_NA_STATE(chunk) == VX_NA_UNIFORM) {
                if (!inside_world(cg, 16)) bad(array + c, "uniform chunk reaches outside the world: ", chunk, "");
                count += chunk_voxels;
            }
            if (VX_NA_STATE(chunk) != VX_NA_MIXED) continue;
            std::uint32_t bi = VX_NA_PAYLOAD(chunk);
            if (out.block_live[bi]++) bad(array + c, "chunk cell shares block array ", bi, " with another chunk");
            std::uint64_t barray = blocks + std::uint64_t(bi) * VX_NA_BLOCK_ARRAY_WORDS;
            for (std::uint32_t b = 0; b < VX_NA_BLOCK_ARRAY_WORDS; ++b) {
                check_cell(barray + b, VX_NA_BLOCK_AADF_BITS, group_cap, "block cell");
                std::uint32_t block = w[barray + b];
                glm::ivec3 bg = cg + glm::ivec3(int(b & 3), int(b >> 2 & 3), int(b >> 4)) * 4;
                bool in = inside_world(bg, 4);
                if (VX_NA_STATE(block) == VX_NA_UNIFORM) {
                    if (!in) bad(barray + b, "uniform block reaches outside the world: ", block, "");
                    count += 64;
                }
                if (VX_NA_STATE(block) != VX_NA_MIXED) continue;
                std::uint32_t gi = VX_NA_PAYLOAD(block);
                ++users[gi];
                std::uint64_t gw = groups + std::uint64_t(gi) * VX_NA_GROUP_WORDS;
                for (std::uint32_t i = 0; i < 64; ++i) {
                    std::uint32_t v = w[gw + VX_NA_VOXEL_WORD(i)] >> VX_NA_VOXEL_SHIFT(i) & 0xFFFFu;
                    bool solid = v & VX_NA_VOXEL_SOLID;
                    if (solid ? ((v & VX_NA_TYPE_MASK) == 0 || (v & VX_NA_TYPE_MASK) > 255) : (v >> 12) != 0)
                        bad(gw + VX_NA_VOXEL_WORD(i), solid ? "voxel type outside 1..255: " : "empty voxel with bits beyond its fields: ", v, "");
                    if (solid && !in && !out.bounds.contains(grid.origin + bg + glm::ivec3(int(i & 3), int(i >> 2 & 3), int(i >> 4))))
                        bad(gw + VX_NA_VOXEL_WORD(i), "solid voxel outside the world: ", v, "");
                    count += solid;
                }
            }
            check_fields(barray, glm::ivec3(4), VX_NA_BLOCK_AADF_BITS, "block");
        }
        check_fields(array, glm::ivec3(16), VX_NA_CHUNK_AADF_BITS, "chunk");
    }
    check_fields(table, grid.pages, VX_NA_PAGE_AADF_BITS, "page");
    // Groups: voxel fields inside their block (as 4^3 cells: solid = uniform), the types
    // into the group table with their users.
    for (std::uint64_t gi = 0; gi < group_cap; ++gi) {
        std::uint64_t gw = groups + gi * VX_NA_GROUP_WORDS;
        voxel_group types{};
        std::uint32_t cells[64];
        for (std::uint32_t i = 0; i < 64; ++i) {
            std::uint32_t v = w[gw + VX_NA_VOXEL_WORD(i)] >> VX_NA_VOXEL_SHIFT(i) & 0xFFFFu;
            cells[i] = v & VX_NA_VOXEL_SOLID ? VX_NA_UNIFORM_CELL(v & VX_NA_TYPE_MASK) : v;
            if (v & VX_NA_VOXEL_SOLID) types[VX_NA_VOXEL_WORD(i)] |= v << VX_NA_VOXEL_SHIFT(i);
        }
        if (users[gi]) {
            std::int64_t i = first_broken_field(cells, glm::ivec3(4), VX_NA_VOXEL_AADF_BITS);
            if (i >= 0) bad(gw + VX_NA_VOXEL_WORD(std::uint64_t(i)), "voxel field's cuboid holds solid voxels or leaves its block: ", cells[i], "");
        }
        out.groups.adopt(types, users[gi]);
    }
    out.voxels = count;
    return out;
}

}  // namespace voxray::naadf_detail
