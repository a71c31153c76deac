// Builds the NAADF blob (naadf/layout.h) from a voxel model (paper section 3.2, on CPU
// threads): every model chunk becomes a chunk of 64 blocks, uniform blocks and chunks
// collapse, mixed blocks share deduplicated voxel groups (naadf/group_table.hpp), then
// chunks are gathered into pages and pages into the page table; every empty cell gets its
// AADF (naadf/aadf.hpp) unless the options say not to.
//
// Chunks are built in parallel in batches; groups are interned and arrays laid out
// serially in (page, chunk) order, so the same model always gives the same bytes.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "voxray/core/blob.hpp"
#include "voxray/core/box.hpp"
#include "voxray/core/error.hpp"
#include "voxray/model/build_threads.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/naadf/aadf.hpp"
#include "voxray/naadf/group_table.hpp"
#include "voxray/naadf/layout.h"

namespace voxray {

struct naadf_options {
    // false: every AADF stays 0. Still exact (a cell then skips only itself), just slower:
    // what a world looks like before its distance fields are grown.
    bool distance_fields = true;
    unsigned threads = 0;  // build threads; 0 = every hardware thread
};

// What a build made, for reports and tests.
struct naadf_stats {
    std::uint64_t pages = 0;         // page table entries
    std::uint64_t mixed_pages = 0;   // = chunk arrays
    std::uint64_t mixed_chunks = 0;  // = block arrays
    std::uint64_t uniform_chunks = 0;
    std::uint64_t mixed_blocks = 0;  // blocks pointing to a group
    std::uint64_t groups = 0;        // distinct voxel groups
};

namespace naadf_detail {

// A page table beyond this many entries (1 GiB) is refused: worlds of 65536^3 voxels need 2^24.
inline constexpr std::uint64_t max_page_table_entries = std::uint64_t(1) << 28;

// One model chunk as NAADF cells, before its groups are interned.
struct built_chunk {
    std::uint32_t cell = 0;                  // uniform, or mixed (index filled in later)
    std::array<std::uint32_t, 64> blocks{};  // mixed blocks hold their local group number
    std::vector<voxel_group> groups;
};

inline int floor_div(int a, int b) { return a >= 0 ? a / b : -((-a + b - 1) / b); }

inline void build_chunk(const voxel_model::chunk& c, bool fields, built_chunk& out) {
    out.groups.clear();
    std::uint64_t solid_blocks = 0;
    bool uniform = true;
    std::uint32_t first_type = 0;
    for (int b = 0; b < 64; ++b) {
        glm::ivec3 base = glm::ivec3(b & 3, (b >> 2) & 3, b >> 4) * 4;
        std::array<std::uint8_t, 64> types;
        std::uint64_t solid = 0;
        for (int i = 0; i < 64; ++i) {
            glm::ivec3 p = base + glm::ivec3(i & 3, (i >> 2) & 3, i >> 4);
            types[i] = c.voxels[voxel_model::local_index(p)];
            solid |= std::uint64_t(types[i] != 0) << i;
        }
        bool same = std::all_of(types.begin(), types.end(), [&](std::uint8_t t) { return t == types[0]; });
        std::uint32_t cell = 0;
        if (solid == 0) {
            uniform = false;
            out.blocks[b] = 0;
            continue;
        }
        solid_blocks |= std::uint64_t(1) << b;
        if (solid == ~std::uint64_t(0) && same) {
            cell = VX_NA_UNIFORM_CELL(std::uint32_t(types[0]));
        } else {
            auto aadfs = fields ? grid4_aadfs(solid, VX_NA_VOXEL_AADF_BITS) : std::array<std::uint32_t, 64>{};
            voxel_group g{};
            for (int i = 0; i < 64; ++i) {
                std::uint32_t v = (solid >> i) & 1u ? VX_NA_SOLID_VOXEL(std::uint32_t(types[i])) : aadfs[i];
                g[VX_NA_VOXEL_WORD(i)] |= v << VX_NA_VOXEL_SHIFT(i);
            }
            cell = VX_NA_MIXED_CELL(std::uint32_t(out.groups.size()));
            out.groups.push_back(g);
        }
        if (b == 0) first_type = cell;
        uniform = uniform && VX_NA_STATE(cell) == VX_NA_UNIFORM && cell == first_type;
        out.blocks[b] = cell;
    }
    if (uniform) {
        out.cell = first_type;
        return;
    }
    if (fields) {
        auto aadfs = grid4_aadfs(solid_blocks, VX_NA_BLOCK_AADF_BITS);
        for (int b = 0; b < 64; ++b)
            if (!((solid_blocks >> b) & 1u)) out.blocks[b] = aadfs[b];
    }
    out.cell = VX_NA_MIXED_CELL(0);
}

// The blob and its figures.
struct naadf_build {
    blob_words words;
    box3i bounds;
    naadf_stats stats;
};

inline naadf_build build(const voxel_model& model, const naadf_options& options) {
    naadf_build out;
    box3i b = model.bounds();
    out.bounds = b;
    glm::ivec3 extent = b.extent();
    constexpr int page_edge = 1 << VX_NA_PAGE_BITS;
    glm::ivec3 grid_origin = b.empty() ? glm::ivec3(0)
                                       : glm::ivec3(floor_div(b.min.x, page_edge), floor_div(b.min.y, page_edge),
                                                    floor_div(b.min.z, page_edge)) * page_edge;
    glm::ivec3 shift = b.empty() ? glm::ivec3(0) : b.min - grid_origin;
    glm::ivec3 pages = glm::max((shift + extent + page_edge - 1) / page_edge, glm::ivec3(1));
    std::uint64_t page_count = std::uint64_t(pages.x) * pages.y * pages.z;
    if (page_count > max_page_table_entries)
        fail("naadf: a world of ", extent.x, " x ", extent.y, " x ", extent.z, " voxels needs ", page_count,
             " page table entries, above the limit of ", max_page_table_entries);
    out.stats.pages = page_count;
    std::uint64_t pages_xy = std::uint64_t(pages.x) * pages.y;

    // Model chunks in (page slot, chunk index) order.
    struct source {
        std::uint64_t key;
        const voxel_model::chunk* chunk;
    };
    std::vector<source> sources;
    sources.reserve(model.chunk_count());
    model.for_each_chunk([&](glm::ivec3 origin, const voxel_model::chunk& c) {
        auto g = glm::uvec3(origin - grid_origin);
        std::uint64_t slot = VX_NA_PAGE_SLOT(std::uint64_t(g.x), std::uint64_t(g.y), std::uint64_t(g.z), std::uint64_t(pages.x), pages_xy);
        sources.push_back({slot << 12 | VX_NA_CHUNK_INDEX(g.x, g.y, g.z), &c});
    });
    std::sort(sources.begin(), sources.end(), [](const source& a, const source& x) { return a.key < x.key; });

    // Chunks, built in parallel batches; groups interned and block arrays laid out in order.
    group_table groups;
    std::vector<std::uint32_t> block_words;
    std::vector<std::uint32_t> chunk_cells(sources.size());
    constexpr std::size_t batch = 4096;
    std::vector<built_chunk> built(std::min(batch, sources.size()));
    for (std::size_t begin = 0; begin < sources.size(); begin += batch) {
        std::size_t n = std::min(batch, sources.size() - begin);
        unsigned threads = resolve_build_threads(options.threads, n);
        run_build_threads(threads, [&](unsigned id) {
            for (std::size_t i = id; i < n; i += threads) build_chunk(*sources[begin + i].chunk, options.distance_fields, built[i]);
        });
        for (std::size_t i = 0; i < n; ++i) {
            built_chunk& c = built[i];
            if (VX_NA_STATE(c.cell) == VX_NA_UNIFORM) {
                chunk_cells[begin + i] = c.cell;
                ++out.stats.uniform_chunks;
                continue;
            }
            for (auto& cell : c.blocks)
                if (VX_NA_STATE(cell) == VX_NA_MIXED) {
                    cell = VX_NA_MIXED_CELL(groups.intern(c.groups[VX_NA_PAYLOAD(cell)]));
                    ++out.stats.mixed_blocks;
                }
            std::uint64_t index = block_words.size() / VX_NA_BLOCK_ARRAY_WORDS;
            if (index > VX_NA_MAX_INDEX) fail("naadf: more than ", VX_NA_MAX_INDEX, " mixed chunks (30-bit index)");
            chunk_cells[begin + i] = VX_NA_MIXED_CELL(std::uint32_t(index));
            block_words.insert(block_words.end(), c.blocks.begin(), c.blocks.end());
        }
    }
    out.stats.mixed_chunks = block_words.size() / VX_NA_BLOCK_ARRAY_WORDS;
    out.stats.groups = groups.size();

    // Pages: each run of chunks with one page slot fills that page's chunk array.
    std::vector<std::uint32_t> page_cells(page_count, 0u);
    std::vector<std::uint8_t> page_solid(page_count, 0);
    std::vector<std::uint32_t> chunk_words;
    std::vector<std::uint8_t> solid(VX_NA_CHUNK_ARRAY_WORDS);
    for (std::size_t begin = 0; begin < sources.size();) {
        std::uint64_t slot = sources[begin].key >> 12;
        std::size_t end = begin;
        std::vector<std::uint32_t> cells(VX_NA_CHUNK_ARRAY_WORDS, 0u);
        std::fill(solid.begin(), solid.end(), 0);
        for (; end < sources.size() && sources[end].key >> 12 == slot; ++end) {
            auto index = sources[end].key & 4095u;
            cells[index] = chunk_cells[end];
            solid[index] = 1;
        }
        bool uniform = end - begin == VX_NA_CHUNK_ARRAY_WORDS && VX_NA_STATE(cells[0]) == VX_NA_UNIFORM &&
                       std::all_of(cells.begin(), cells.end(), [&](std::uint32_t c) { return c == cells[0]; });
        if (uniform) {
            page_cells[slot] = cells[0];
        } else {
            if (options.distance_fields) {
                auto aadfs = grid_aadfs(glm::ivec3(16), solid, 15, VX_NA_CHUNK_AADF_BITS);
                for (int i = 0; i < VX_NA_CHUNK_ARRAY_WORDS; ++i)
                    if (!solid[i]) cells[i] = aadfs[i];
            }
            page_cells[slot] = VX_NA_MIXED_CELL(std::uint32_t(chunk_words.size() / VX_NA_CHUNK_ARRAY_WORDS));
            chunk_words.insert(chunk_words.end(), cells.begin(), cells.end());
        }
        page_solid[slot] = 1;
        begin = end;
    }
    out.stats.mixed_pages = chunk_words.size() / VX_NA_CHUNK_ARRAY_WORDS;
    if (options.distance_fields) {
        auto aadfs = grid_aadfs(pages, page_solid, 31, VX_NA_PAGE_AADF_BITS);
        for (std::uint64_t i = 0; i < page_count; ++i)
            if (!page_solid[i]) page_cells[i] = aadfs[i];
    }

    // The blob: header, page table, chunk arrays, block arrays, groups.
    std::uint64_t table = VX_NA_HEADER_WORDS;
    std::uint64_t chunks = table + page_count;
    std::uint64_t blocks = chunks + chunk_words.size();
    std::uint64_t voxels = blocks + block_words.size();
    std::uint64_t total = voxels + groups.words().size();
    check_blob_size("naadf", total);
    blob_words& w = out.words;
    w.assign(VX_NA_HEADER_WORDS, 0u);
    w.reserve(total);
    w[VX_NA_HEADER_MAGIC] = VX_NA_MAGIC;
    w[VX_NA_HEADER_VERSION] = VX_NA_VERSION;
    for (int a = 0; a < 3; ++a) {
        w[VX_NA_HEADER_ORIGIN + a] = std::uint32_t(b.min[a]);
        w[VX_NA_HEADER_EXTENT + a] = std::uint32_t(extent[a]);
        w[VX_NA_HEADER_SHIFT + a] = std::uint32_t(shift[a]);
        w[VX_NA_HEADER_PAGES_DIM + a] = std::uint32_t(pages[a]);
    }
    w[VX_NA_HEADER_PAGE_TABLE] = std::uint32_t(table);
    w[VX_NA_HEADER_CHUNKS] = std::uint32_t(chunks);
    w[VX_NA_HEADER_BLOCKS] = std::uint32_t(blocks);
    w[VX_NA_HEADER_VOXELS] = std::uint32_t(voxels);
    w[VX_NA_HEADER_CHUNK_ARRAYS] = std::uint32_t(out.stats.mixed_pages);
    w[VX_NA_HEADER_BLOCK_ARRAYS] = std::uint32_t(out.stats.mixed_chunks);
    w[VX_NA_HEADER_GROUPS] = std::uint32_t(out.stats.groups);
    w.insert(w.end(), page_cells.begin(), page_cells.end());
    w.insert(w.end(), chunk_words.begin(), chunk_words.end());
    w.insert(w.end(), block_words.begin(), block_words.end());
    w.insert(w.end(), groups.words().begin(), groups.words().end());
    return out;
}

}  // namespace naadf_detail
}  // namespace voxray
