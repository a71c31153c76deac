// The editable NAADF blob (naadf/layout.h): the header, the page table and three areas
// (chunk arrays, block arrays, voxel groups), each with spare capacity so that edits add
// arrays and groups in place, and free lists so that arrays edits make unreachable are
// reused. Cells name arrays by index, never by word offset, so growing an area only
// moves the areas behind it and rewrites the header's offsets: a re-layout, after which
// the whole blob is dirty. Every other change marks just the words it wrote.
//
// Plain data: naadf guards it with its lock.
#pragma once
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "voxray/core/blob.hpp"
#include "voxray/core/error.hpp"
#include "voxray/core/word_range.hpp"
#include "voxray/naadf/layout.h"
#include "voxray/sync/dirty_set.hpp"

namespace voxray::naadf_detail {

class cell_store {
public:
    // Growth past this many bytes fails (checked before anything changes).
    void limit(std::uint64_t max_bytes) { max_bytes_ = max_bytes; }

    // Takes a built blob (areas packed, header counts = arrays used) and gives each area
    // `headroom` (a fraction) of spare capacity; `used_*` are the arrays and groups in use.
    void adopt(blob_words words, double headroom) {
        words_ = std::move(words);
        read_header();
        chunk_free_.clear();
        block_free_.clear();
        auto spare = [&](std::uint32_t n) { return std::uint32_t(std::min<double>(VX_NA_MAX_INDEX, n + n * headroom)); };
        relayout(pages(), spare(chunk_cap_), spare(block_cap_), spare(group_cap_));
        chunk_used_ = chunk_cap_used_at_adopt_;
        block_used_ = block_cap_used_at_adopt_;
    }

    std::span<const std::uint32_t> blob() const { return words_; }
    std::uint32_t* words() { return words_.data(); }
    const std::uint32_t* words() const { return words_.data(); }

    std::uint64_t pages() const { return std::uint64_t(words_[VX_NA_HEADER_CHUNKS] - words_[VX_NA_HEADER_PAGE_TABLE]); }
    std::uint32_t* page_cell(std::uint64_t slot) { return words_.data() + table_ + slot; }
    std::uint32_t* chunk_array(std::uint32_t i) { return words_.data() + chunks_ + std::uint64_t(i) * VX_NA_CHUNK_ARRAY_WORDS; }
    std::uint32_t* block_array(std::uint32_t i) { return words_.data() + blocks_ + std::uint64_t(i) * VX_NA_BLOCK_ARRAY_WORDS; }
    std::uint32_t* group(std::uint32_t i) { return words_.data() + voxels_ + std::uint64_t(i) * VX_NA_GROUP_WORDS; }
    const std::uint32_t* page_cell(std::uint64_t slot) const { return words_.data() + table_ + slot; }
    const std::uint32_t* chunk_array(std::uint32_t i) const { return words_.data() + chunks_ + std::uint64_t(i) * VX_NA_CHUNK_ARRAY_WORDS; }
    const std::uint32_t* block_array(std::uint32_t i) const { return words_.data() + blocks_ + std::uint64_t(i) * VX_NA_BLOCK_ARRAY_WORDS; }
    const std::uint32_t* group(std::uint32_t i) const { return words_.data() + voxels_ + std::uint64_t(i) * VX_NA_GROUP_WORDS; }

    // Arrays in use and capacity, for stats and the memory tests.
    std::uint32_t chunk_arrays_used() const { return chunk_used_ - std::uint32_t(chunk_free_.size()); }
    std::uint32_t block_arrays_used() const { return block_used_ - std::uint32_t(block_free_.size()); }

    // A chunk array (4096 cells) or block array (64 cells) for a new mixed page or chunk:
    // a freed one first, else the next unused one, growing the area when it is full (a
    // re-layout: pointers into the blob taken before are stale).
    std::uint32_t alloc_chunk_array() {
        if (!chunk_free_.empty()) return pop(chunk_free_);
        if (chunk_used_ == chunk_cap_) relayout(pages(), more(chunk_cap_), block_cap_, group_cap_);
        return chunk_used_++;
    }
    std::uint32_t alloc_block_array() {
        if (!block_free_.empty()) return pop(block_free_);
        if (block_used_ == block_cap_) relayout(pages(), chunk_cap_, more(block_cap_), group_cap_);
        return block_used_++;
    }
    void free_chunk_array(std::uint32_t i) { chunk_free_.push_back(i); }
    void free_block_array(std::uint32_t i) { block_free_.push_back(i); }
    // Room for groups with indices below n.
    void reserve_groups(std::uint64_t n) {
        if (n > group_cap_) relayout(pages(), chunk_cap_, block_cap_, more(std::uint32_t(std::min<std::uint64_t>(n, VX_NA_MAX_INDEX))));
    }

    // A new page table of `page_count` cells (world growth), filled by the caller; the
    // areas keep their contents. Whole blob dirty.
    void resize_table(std::uint64_t page_count) { relayout(page_count, chunk_cap_, block_cap_, group_cap_); }

    // Which arrays and groups are in use, from the cells (after loading a file): the rest
    // go to the free lists. `chunk_live` / `block_live` have one flag per array.
    void set_in_use(const std::vector<std::uint8_t>& chunk_live, const std::vector<std::uint8_t>& block_live) {
        chunk_used_ = chunk_cap_;
        block_used_ = block_cap_;
        chunk_free_.clear();
        block_free_.clear();
        for (std::uint32_t i = chunk_cap_; i-- > 0;)
            if (!chunk_live[i]) chunk_free_.push_back(i);
        for (std::uint32_t i = block_cap_; i-- > 0;)
            if (!block_live[i]) block_free_.push_back(i);
    }
    std::uint32_t chunk_capacity() const { return chunk_cap_; }
    std::uint32_t block_capacity() const { return block_cap_; }
    std::uint32_t group_capacity() const { return group_cap_; }

    // ---- what changed (for tracer updates) ----
    void mark(const std::uint32_t* first, std::uint32_t count) {
        dirty_.add_range({std::uint32_t(first - words_.data()), count});
    }
    // Mutable through const: committing the dirty set to a change log is not a change of
    // the blob (naadf::snapshot is const).
    dirty_set& dirty() const { return dirty_; }

private:
    static std::uint32_t pop(std::vector<std::uint32_t>& list) {
        std::uint32_t i = list.back();
        list.pop_back();
        return i;
    }
    // Capacity after growth: half again, and never less than a few arrays.
    static std::uint32_t more(std::uint32_t cap) {
        return std::uint32_t(std::min<std::uint64_t>(VX_NA_MAX_INDEX, std::uint64_t(cap) + cap / 2 + 16));
    }

    void read_header() {
        table_ = words_[VX_NA_HEADER_PAGE_TABLE];
        chunks_ = words_[VX_NA_HEADER_CHUNKS];
        blocks_ = words_[VX_NA_HEADER_BLOCKS];
        voxels_ = words_[VX_NA_HEADER_VOXELS];
        chunk_cap_ = chunk_cap_used_at_adopt_ = words_[VX_NA_HEADER_CHUNK_ARRAYS];
        block_cap_ = block_cap_used_at_adopt_ = words_[VX_NA_HEADER_BLOCK_ARRAYS];
        group_cap_ = words_[VX_NA_HEADER_GROUPS];
    }

    // Lays the blob out again with these sizes, keeping every area's contents (a smaller
    // page table keeps its first cells; the caller rewrites the table anyway).
    void relayout(std::uint64_t page_count, std::uint32_t chunk_cap, std::uint32_t block_cap, std::uint32_t group_cap) {
        std::uint64_t table = VX_NA_HEADER_WORDS;
        std::uint64_t chunks = table + page_count;
        std::uint64_t blocks = chunks + std::uint64_t(chunk_cap) * VX_NA_CHUNK_ARRAY_WORDS;
        std::uint64_t voxels = blocks + std::uint64_t(block_cap) * VX_NA_BLOCK_ARRAY_WORDS;
        std::uint64_t total = voxels + std::uint64_t(group_cap) * VX_NA_GROUP_WORDS;
        check_blob_size("naadf", total);
        if (total * 4 > max_bytes_)
            fail("naadf: the blob would grow to ", total * 4, " bytes, above this structure's limit of ", max_bytes_,
                 " bytes (naadf_options::max_blob_bytes)");
        blob_words w(total, 0u);
        std::copy_n(words_.begin(), VX_NA_HEADER_WORDS, w.begin());
        auto move_area = [&](std::uint64_t from, std::uint64_t old_words, std::uint64_t to, std::uint64_t new_words) {
            std::copy_n(words_.begin() + from, std::min(old_words, new_words), w.begin() + to);
        };
        move_area(table_, pages(), table, page_count);
        move_area(chunks_, std::uint64_t(chunk_cap_) * VX_NA_CHUNK_ARRAY_WORDS, chunks, std::uint64_t(chunk_cap) * VX_NA_CHUNK_ARRAY_WORDS);
        move_area(blocks_, std::uint64_t(block_cap_) * VX_NA_BLOCK_ARRAY_WORDS, blocks, std::uint64_t(block_cap) * VX_NA_BLOCK_ARRAY_WORDS);
        move_area(voxels_, std::uint64_t(group_cap_) * VX_NA_GROUP_WORDS, voxels, std::uint64_t(group_cap) * VX_NA_GROUP_WORDS);
        w[VX_NA_HEADER_PAGE_TABLE] = std::uint32_t(table);
        w[VX_NA_HEADER_CHUNKS] = std::uint32_t(chunks);
        w[VX_NA_HEADER_BLOCKS] = std::uint32_t(blocks);
        w[VX_NA_HEADER_VOXELS] = std::uint32_t(voxels);
        w[VX_NA_HEADER_CHUNK_ARRAYS] = chunk_cap;
        w[VX_NA_HEADER_BLOCK_ARRAYS] = block_cap;
        w[VX_NA_HEADER_GROUPS] = group_cap;
        words_.swap(w);
        table_ = std::uint32_t(table);
        chunks_ = std::uint32_t(chunks);
        blocks_ = std::uint32_t(blocks);
        voxels_ = std::uint32_t(voxels);
        chunk_cap_ = chunk_cap;
        block_cap_ = block_cap;
        group_cap_ = group_cap;
        dirty_.clear();
        dirty_.mark_whole();
    }

    blob_words words_;
    std::uint64_t max_bytes_ = (max_blob_words - 1) * 4;
    std::uint32_t table_ = 0, chunks_ = 0, blocks_ = 0, voxels_ = 0;
    std::uint32_t chunk_cap_ = 0, block_cap_ = 0, group_cap_ = 0;
    std::uint32_t chunk_used_ = 0, block_used_ = 0;  // high-water marks
    std::uint32_t chunk_cap_used_at_adopt_ = 0, block_cap_used_at_adopt_ = 0;
    std::vector<std::uint32_t> chunk_free_, block_free_;
    mutable dirty_set dirty_;
};

}  // namespace voxray::naadf_detail
