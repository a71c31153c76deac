// NAADF's upkeep between and after edits (declared in naadf/naadf.hpp): settling the pages
// an edit touched (reset broken chunk fields, collapse empty and uniform pages, check the
// page table's fields), refine() growing fields back, world growth, and the figures.
#pragma once
#include <algorithm>
#include <atomic>
#include <vector>

#include "voxray/edit/world_growth.hpp"
#include "voxray/model/build_threads.hpp"
#include "voxray/naadf/field_repair.hpp"
#include "voxray/naadf/naadf.hpp"

namespace voxray {

VOXRAY_HOST_INLINE void naadf::settle_pages() {
    bool table_check = false;
    for (std::uint64_t slot : touched_) {
        unsigned flags = touched_flag_[slot];
        touched_flag_[slot] = 0;
        std::uint32_t* cell = store_.page_cell(slot);
        if (VX_NA_STATE(*cell) != VX_NA_MIXED) continue;
        std::uint32_t index = VX_NA_PAYLOAD(*cell);
        std::uint32_t* array = store_.chunk_array(index);
        naadf_detail::page_cells regrow;  // the chunks whose fields refine() must grow
        if (flags & page_was_empty) regrow.set();  // its chunks start with field 0
        if (flags & chunk_filled)
            naadf_detail::reset_broken_fields(array, glm::ivec3(16), VX_NA_CHUNK_AADF_BITS, [&](std::size_t i) {
                store_.mark(array + i, 1);
                regrow.set(i);
            });
        if (auto e = emptied_.find(slot); e != emptied_.end()) regrow |= e->second | naadf_detail::near_emptied(array, e->second);
        std::uint32_t* end = array + VX_NA_CHUNK_ARRAY_WORDS;
        bool all_empty = std::all_of(array, end, [](std::uint32_t c) { return VX_NA_STATE(c) == VX_NA_EMPTY; });
        bool all_same = VX_NA_STATE(array[0]) == VX_NA_UNIFORM && std::all_of(array, end, [&](std::uint32_t c) { return c == array[0]; });
        if (!all_empty && (flags & page_was_empty)) table_check = true;
        if (all_empty || all_same) {  // collapse: the page cell says it all
            *cell = all_empty ? 0u : array[0];
            store_.mark(cell, 1);
            store_.free_chunk_array(index);
            table_stale_ |= all_empty;
            continue;
        }
        if (regrow.any()) mark_stale(slot, regrow);
    }
    touched_.clear();
    emptied_.clear();
    if (table_check) {
        std::uint32_t* table = store_.page_cell(0);
        naadf_detail::reset_broken_fields(table, grid_.pages, VX_NA_PAGE_AADF_BITS, [&](std::size_t i) { store_.mark(table + i, 1); });
        table_stale_ = true;
    }
}

VOXRAY_HOST_INLINE naadf_refine_progress naadf::refine(std::size_t budget, unsigned threads) {
    std::unique_lock lock(locks_.m);
    // Up to `budget` pages from the back of the list, regrown in parallel (each page's
    // chunk array is its own), then their changed words marked in order.
    std::size_t n = std::min(budget, stale_.size());
    std::vector<stale_page> pages(stale_.end() - std::ptrdiff_t(n), stale_.end());
    stale_.resize(stale_.size() - n);
    for (auto& page : pages) stale_at_[page.slot] = 0;
    std::vector<std::vector<std::uint32_t>> changed(n);
    std::atomic<std::size_t> next{0};
    run_build_threads(resolve_build_threads(threads, n), [&](unsigned) {
        for (std::size_t k; (k = next.fetch_add(1)) < n;) {
            std::uint32_t cell = *store_.page_cell(pages[k].slot);
            if (VX_NA_STATE(cell) != VX_NA_MIXED) continue;
            naadf_detail::regrow_page_fields(store_.chunk_array(VX_NA_PAYLOAD(cell)), pages[k].cells,
                                             [&](std::size_t i) { changed[k].push_back(std::uint32_t(i)); });
        }
    });
    for (std::size_t k = 0; k < n; ++k) {
        if (changed[k].empty()) continue;  // (a page that is no longer mixed has no array)
        std::uint32_t* array = store_.chunk_array(VX_NA_PAYLOAD(*store_.page_cell(pages[k].slot)));
        for (std::uint32_t i : changed[k]) store_.mark(array + i, 1);
    }
    if (budget > n && table_stale_) {
        std::uint32_t* table = store_.page_cell(0);
        naadf_detail::regrow_fields(table, grid_.pages, 31, VX_NA_PAGE_AADF_BITS, [&](std::size_t i) { store_.mark(table + i, 1); });
        table_stale_ = false;
    }
    return {stale_.size(), table_stale_};
}

VOXRAY_HOST_INLINE void naadf::make_room(const regions::box64& need) {
    const box3i& world = grid_.bounds;
    if (need.inside(world) || outside_ == outside_edits::clip) return;
    if (outside_ == outside_edits::fail) world_growth::refuse(world, need, "naadf");
    regrid(world.empty() ? need.saturated() : world_growth::grown(world, need, 1 << VX_NA_PAGE_BITS, "naadf"));
}

// The world grows to `world`: the same page table when it still covers it (only the
// header moves), else a bigger table with the old pages copied to their new slots (a
// re-layout: the blob is sent whole once).
VOXRAY_HOST_INLINE void naadf::regrid(const box3i& world) {
    naadf_detail::grid_placement next(world);
    if (next.origin == grid_.origin && next.pages == grid_.pages) {
        grid_ = next;
        next.write_header(store_.words());
        store_.mark(store_.words() + VX_NA_HEADER_ORIGIN, VX_NA_HEADER_PAGE_TABLE - VX_NA_HEADER_ORIGIN);
        return;
    }
    std::vector<std::uint32_t> old(store_.page_cell(0), store_.page_cell(0) + grid_.page_count);
    glm::ivec3 move = (grid_.origin - next.origin) >> VX_NA_PAGE_BITS;
    store_.resize_table(next.page_count);
    std::uint32_t* table = store_.page_cell(0);
    std::fill_n(table, next.page_count, 0u);
    auto new_slot = [&](std::uint64_t slot) {
        std::uint64_t px = grid_.pages.x, py = grid_.pages.y;
        glm::u64vec3 p(slot % px + move.x, slot / px % py + move.y, slot / px / py + move.z);
        return p.x + std::uint64_t(next.pages.x) * (p.y + std::uint64_t(next.pages.y) * p.z);
    };
    // Old fields stay valid (the new pages are empty) but are capped at the old table's
    // edges: refine() grows them across the new space. An empty world's one page is empty
    // and placed nowhere: its origin need not lie inside the new grid (clang's UBSan caught
    // the negative slot it got).
    if (!grid_.bounds.empty()) {
        for (std::uint64_t slot = 0; slot < old.size(); ++slot) table[new_slot(slot)] = old[slot];
        for (auto& page : stale_) page.slot = new_slot(page.slot);
    }
    stale_at_.assign(next.page_count, 0);
    for (std::size_t i = 0; i < stale_.size(); ++i) stale_at_[stale_[i].slot] = std::uint32_t(i + 1);
    touched_flag_.assign(next.page_count, 0);
    grid_ = next;
    next.write_header(store_.words());
    table_stale_ = true;
}

VOXRAY_HOST_INLINE naadf_stats naadf::stats() const {
    std::shared_lock lock(locks_.m);
    naadf_stats s;
    s.pages = grid_.page_count;
    s.mixed_pages = store_.chunk_arrays_used();
    s.mixed_chunks = store_.block_arrays_used();
    s.groups = groups_.live();
    for (std::uint64_t slot = 0; slot < grid_.page_count; ++slot) {
        std::uint32_t page = *store_.page_cell(slot);
        if (VX_NA_STATE(page) != VX_NA_MIXED) continue;
        const std::uint32_t* chunks = store_.chunk_array(VX_NA_PAYLOAD(page));
        for (int c = 0; c < VX_NA_CHUNK_ARRAY_WORDS; ++c) {
            s.uniform_chunks += VX_NA_STATE(chunks[c]) == VX_NA_UNIFORM;
            if (VX_NA_STATE(chunks[c]) != VX_NA_MIXED) continue;
            const std::uint32_t* blocks = store_.block_array(VX_NA_PAYLOAD(chunks[c]));
            for (int b = 0; b < 64; ++b) s.mixed_blocks += VX_NA_STATE(blocks[b]) == VX_NA_MIXED;
        }
    }
    return s;
}

}  // namespace voxray
