// Builds the NAADF blob (naadf/layout.h) from a voxel model (paper section 3.2, on CPU
// threads): every model chunk becomes a chunk of 64 blocks (naadf/chunk_cells.hpp), mixed
// blocks share deduplicated voxel groups (naadf/group_table.hpp), chunks are gathered into
// pages and pages into the page table (naadf/page_cells.hpp); every empty cell gets its
// AADF (naadf/aadf.hpp) unless the options say not to.
//
// Chunks are built in parallel in batches; groups are interned and block arrays laid out
// serially in (page, chunk) order, so the same model always gives the same bytes.
#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "voxray/core/blob.hpp"
#include "voxray/core/box.hpp"
#include "voxray/core/error.hpp"
#include "voxray/edit/world_growth.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/naadf/chunk_cells.hpp"
#include "voxray/naadf/layout.h"
#include "voxray/naadf/page_cells.hpp"

namespace voxray {

struct naadf_options {
    // false: every AADF stays 0. Still exact (a cell then skips only itself), just slower:
    // what a world looks like before its distance fields are grown.
    bool distance_fields = true;
    // true: voxel and block fields are built, chunk and page fields are left at 0 for
    // naadf::refine(budget) to grow later (a faster build, traceable at once).
    bool defer_chunk_fields = false;
    unsigned threads = 0;  // build threads; 0 = every hardware thread
    // Spare capacity of each blob area after the build, as a fraction of what it used, so
    // that the first edits do not re-lay the blob out (which resends it whole).
    double headroom = 0.25;
    outside_edits outside = outside_edits::grow;  // fills outside bounds(): edit/world_growth.hpp
    // The largest blob edits may grow this structure to (at most, and by default, the
    // 8 GiB of 32-bit word offsets). An edit that needs more fails with voxray::error and
    // leaves the structure consistent: whole chunks applied, every field correct.
    std::uint64_t max_blob_bytes = (max_blob_words - 1) * 4;
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

// a / b rounded down (b > 0), for every int a (INT_MIN included: 64-bit inside).
inline int floor_div(int a, int b) {
    std::int64_t wide = a;
    return int(wide >= 0 ? wide / b : -((-wide + b - 1) / b));
}

// Where the cell grid lies: aligned to pages in world coordinates, so that model chunks
// are chunks; the walk's voxel (0,0,0) is the model's min corner, at grid coordinate shift.
struct grid_placement {
    box3i bounds;
    glm::ivec3 origin{0}, shift{0}, pages{1};
    std::uint64_t page_count = 1;

    explicit grid_placement(const box3i& b) : bounds(b) {
        constexpr int edge = 1 << VX_NA_PAGE_BITS;
        if (b.empty()) return;
        origin = glm::ivec3(floor_div(b.min.x, edge), floor_div(b.min.y, edge), floor_div(b.min.z, edge)) * edge;
        shift = b.min - origin;
        // In 64 bits: an extent near 2^31 would overflow int here.
        glm::i64vec3 n = (glm::i64vec3(shift) + glm::i64vec3(b.extent()) + std::int64_t(edge - 1)) / std::int64_t(edge);
        for (int a = 0; a < 3; ++a)
            if (std::int64_t(origin[a]) + n[a] * edge - 1 > std::numeric_limits<int>::max())
                fail("naadf: a world reaching voxel ", std::int64_t(b.max[a]) - 1, " on axis ", "xyz"[a],
                     " ends past 32-bit coordinates once its last page is whole (pages end at ",
                     std::int64_t(origin[a]) + n[a] * edge, ")");
        pages = glm::ivec3(n);
        page_count = std::uint64_t(n.x) * std::uint64_t(n.y) * std::uint64_t(n.z);
        if (page_count > max_page_table_entries)
            fail("naadf: a world of ", b.extent().x, " x ", b.extent().y, " x ", b.extent().z, " voxels needs ",
                 page_count, " page table entries, above the limit of ", max_page_table_entries);
    }
    // The header words that place the grid (origin, extent, shift, page table size).
    void write_header(std::uint32_t* w) const {
        glm::ivec3 extent = bounds.extent();
        for (int a = 0; a < 3; ++a) {
            w[VX_NA_HEADER_ORIGIN + a] = std::uint32_t(bounds.min[a]);
            w[VX_NA_HEADER_EXTENT + a] = std::uint32_t(extent[a]);
            w[VX_NA_HEADER_SHIFT + a] = std::uint32_t(shift[a]);
            w[VX_NA_HEADER_PAGES_DIM + a] = std::uint32_t(pages[a]);
        }
    }
    // The sort key of the chunk at world position `chunk_origin`: page slot << 12 | index.
    std::uint64_t key(glm::ivec3 chunk_origin) const {
        auto g = glm::uvec3(chunk_origin - origin);
        std::uint64_t slot = VX_NA_PAGE_SLOT(std::uint64_t(g.x), std::uint64_t(g.y), std::uint64_t(g.z),
                                             std::uint64_t(pages.x), std::uint64_t(pages.x) * pages.y);
        return slot << 12 | VX_NA_CHUNK_INDEX(g.x, g.y, g.z);
    }
};

// Every model chunk's cell, in key order, with the block arrays and the groups they use.
struct chunk_level {
    std::vector<std::uint64_t> keys;
    std::vector<std::uint32_t> cells;
    std::vector<std::uint32_t> blocks;  // 64 cells per mixed chunk
    group_table groups;
};

inline void build_chunks(const voxel_model& model, const grid_placement& grid, const naadf_options& options,
                         chunk_level& out, naadf_stats& stats) {
    std::vector<std::pair<std::uint64_t, const voxel_model::chunk*>> sources;
    sources.reserve(model.chunk_count());
    model.for_each_chunk([&](glm::ivec3 origin, const voxel_model::chunk& c) { sources.emplace_back(grid.key(origin), &c); });
    std::sort(sources.begin(), sources.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    out.keys.resize(sources.size());
    out.cells.resize(sources.size());
    out.blocks.reserve(sources.size() * VX_NA_BLOCK_ARRAY_WORDS);  // the most it can take

    constexpr std::size_t batch = 4096;
    std::vector<built_chunk> built(std::min(batch, sources.size()));
    for (std::size_t begin = 0; begin < sources.size(); begin += batch) {
        std::size_t n = std::min(batch, sources.size() - begin);
        unsigned threads = resolve_build_threads(options.threads, n);
        run_build_threads(threads, [&](unsigned id) {
            for (std::size_t i = id; i < n; i += threads) build_chunk(*sources[begin + i].second, options.distance_fields, built[i]);
        });
        for (std::size_t i = 0; i < n; ++i) {
            built_chunk& c = built[i];
            out.keys[begin + i] = sources[begin + i].first;
            if (VX_NA_STATE(c.cell) == VX_NA_UNIFORM) {
                out.cells[begin + i] = c.cell;
                ++stats.uniform_chunks;
                continue;
            }
            for (auto& cell : c.blocks)
                if (VX_NA_STATE(cell) == VX_NA_MIXED) {
                    cell = VX_NA_MIXED_CELL(out.groups.intern(c.groups[VX_NA_PAYLOAD(cell)]));
                    ++stats.mixed_blocks;
                }
            std::uint64_t index = out.blocks.size() / VX_NA_BLOCK_ARRAY_WORDS;
            if (index > VX_NA_MAX_INDEX) fail("naadf: more than ", VX_NA_MAX_INDEX, " mixed chunks (30-bit index)");
            out.cells[begin + i] = VX_NA_MIXED_CELL(std::uint32_t(index));
            out.blocks.insert(out.blocks.end(), c.blocks.begin(), c.blocks.end());
        }
    }
    stats.mixed_chunks = out.blocks.size() / VX_NA_BLOCK_ARRAY_WORDS;
    stats.groups = out.groups.size();
}

// The blob and its figures.
struct naadf_build {
    blob_words words;
    box3i bounds;
    naadf_stats stats;
    group_table groups;  // the groups' types, for edits
};

inline naadf_build build(const voxel_model& model, const naadf_options& options) {
    naadf_build out;
    grid_placement grid(model.bounds());
    out.bounds = grid.bounds;
    out.stats.pages = grid.page_count;
    chunk_level chunks;
    build_chunks(model, grid, options, chunks, out.stats);
    bool chunk_fields = options.distance_fields && !options.defer_chunk_fields;
    page_level pages = build_pages(chunks.keys, chunks.cells, grid.pages, chunk_fields, options.threads);
    out.stats.mixed_pages = pages.chunks.size() / VX_NA_CHUNK_ARRAY_WORDS;

    // The blob: header, page table, chunk arrays, block arrays, groups.
    std::uint64_t table = VX_NA_HEADER_WORDS;
    std::uint64_t chunk_area = table + pages.table.size();
    std::uint64_t block_area = chunk_area + pages.chunks.size();
    std::uint64_t voxel_area = block_area + chunks.blocks.size();
    std::uint64_t total = voxel_area + chunks.groups.size() * VX_NA_GROUP_WORDS;
    check_blob_size("naadf", total);
    blob_words& w = out.words;
    w.resize(total);
    w[VX_NA_HEADER_MAGIC] = VX_NA_MAGIC;
    w[VX_NA_HEADER_VERSION] = VX_NA_VERSION;
    grid.write_header(w.data());
    w[VX_NA_HEADER_PAGE_TABLE] = std::uint32_t(table);
    w[VX_NA_HEADER_CHUNKS] = std::uint32_t(chunk_area);
    w[VX_NA_HEADER_BLOCKS] = std::uint32_t(block_area);
    w[VX_NA_HEADER_VOXELS] = std::uint32_t(voxel_area);
    w[VX_NA_HEADER_CHUNK_ARRAYS] = std::uint32_t(out.stats.mixed_pages);
    w[VX_NA_HEADER_BLOCK_ARRAYS] = std::uint32_t(out.stats.mixed_chunks);
    w[VX_NA_HEADER_GROUPS] = std::uint32_t(out.stats.groups);
    std::copy(pages.table.begin(), pages.table.end(), w.begin() + table);
    std::copy(pages.chunks.begin(), pages.chunks.end(), w.begin() + chunk_area);
    std::copy(chunks.blocks.begin(), chunks.blocks.end(), w.begin() + block_area);
    chunks.groups.copy_to(w.data() + voxel_area);
    if (options.distance_fields) add_group_fields(w.data() + voxel_area, chunks.groups.size(), options.threads);
    out.groups = std::move(chunks.groups);
    return out;
}

}  // namespace naadf_detail
}  // namespace voxray
