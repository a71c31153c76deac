// The page level of NAADF: chunks gathered into pages of 16^3 (each page's chunk array,
// with the empty chunks' AADFs inside the page), then the page table, whose empty pages
// carry AADFs across the table (up to 31 pages a direction). A page whose 4096 chunks are
// all uniform with one type collapses into a uniform page.
#pragma once
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "voxray/model/build_threads.hpp"
#include "voxray/naadf/aadf.hpp"
#include "voxray/naadf/layout.h"

namespace voxray::naadf_detail {

struct page_level {
    std::vector<std::uint32_t> table;   // one cell per page
    std::vector<std::uint32_t> chunks;  // 4096 cells per mixed page
};

// `keys` (sorted) are page slot << 12 | chunk index, `cells` the cell of each such chunk.
inline page_level build_pages(std::span<const std::uint64_t> keys, std::span<const std::uint32_t> cells,
                              glm::ivec3 pages, bool fields, unsigned requested_threads) {
    page_level out;
    std::uint64_t page_count = std::uint64_t(pages.x) * pages.y * pages.z;
    out.table.assign(page_count, 0u);
    std::vector<std::size_t> runs;  // the first chunk of each page, then keys.size()
    for (std::size_t i = 0; i < keys.size(); ++i)
        if (i == 0 || keys[i] >> 12 != keys[i - 1] >> 12) runs.push_back(i);
    runs.push_back(keys.size());
    std::size_t page_runs = runs.size() - 1;

    // Each page's chunk array and its fields, in parallel, page by page.
    out.chunks.assign(page_runs * VX_NA_CHUNK_ARRAY_WORDS, 0u);
    std::vector<std::uint8_t> uniform(page_runs, 0);
    unsigned threads = resolve_build_threads(requested_threads, page_runs);
    run_build_threads(threads, [&](unsigned id) {
        std::vector<std::uint8_t> solid(VX_NA_CHUNK_ARRAY_WORDS);
        for (std::size_t r = id; r < page_runs; r += threads) {
            std::uint32_t* array = out.chunks.data() + r * VX_NA_CHUNK_ARRAY_WORDS;
            std::fill(solid.begin(), solid.end(), 0);
            for (std::size_t i = runs[r]; i < runs[r + 1]; ++i) {
                auto index = keys[i] & 4095u;
                array[index] = cells[i];
                solid[index] = 1;
            }
            if (runs[r + 1] - runs[r] == VX_NA_CHUNK_ARRAY_WORDS && VX_NA_STATE(array[0]) == VX_NA_UNIFORM &&
                std::all_of(array, array + VX_NA_CHUNK_ARRAY_WORDS, [&](std::uint32_t c) { return c == array[0]; })) {
                uniform[r] = 1;
                continue;
            }
            if (!fields) continue;
            auto aadfs = grid_aadfs(glm::ivec3(16), solid, 15, VX_NA_CHUNK_AADF_BITS);
            for (int i = 0; i < VX_NA_CHUNK_ARRAY_WORDS; ++i)
                if (!solid[i]) array[i] = aadfs[i];
        }
    });

    // Uniform pages drop their chunk arrays; the others are numbered in order.
    std::vector<std::uint8_t> page_solid(page_count, 0);
    std::size_t kept = 0;
    for (std::size_t r = 0; r < page_runs; ++r) {
        std::uint64_t slot = keys[runs[r]] >> 12;
        page_solid[slot] = 1;
        if (uniform[r]) {
            out.table[slot] = out.chunks[r * VX_NA_CHUNK_ARRAY_WORDS];
            continue;
        }
        if (kept != r)
            std::copy_n(out.chunks.begin() + r * VX_NA_CHUNK_ARRAY_WORDS, VX_NA_CHUNK_ARRAY_WORDS,
                        out.chunks.begin() + kept * VX_NA_CHUNK_ARRAY_WORDS);
        out.table[slot] = VX_NA_MIXED_CELL(std::uint32_t(kept++));
    }
    out.chunks.resize(kept * VX_NA_CHUNK_ARRAY_WORDS);
    if (fields) {
        auto aadfs = grid_aadfs(pages, page_solid, 31, VX_NA_PAGE_AADF_BITS);
        for (std::uint64_t i = 0; i < page_count; ++i)
            if (!page_solid[i]) out.table[i] = aadfs[i];
    }
    return out;
}

}  // namespace voxray::naadf_detail
