// The brickmap blob's geometry: header, page table, page pool and brick pool offsets
// (brickmap/layout.h), the world box, and relayout() that grows the page or brick
// area in place of the old blob. The brick payload is not its business (brick_codec).
//
//   world (voxels) --/edge--> top cells --/16--> pages (a 16^3 block of cells)
//   page table: pages_dim.x * pages_dim.y * pages_dim.z words, x fastest
#pragma once
#include <algorithm>
#include <cstdint>
#include <limits>

#include <glm/vec3.hpp>

#include "voxray/core/box.hpp"
#include "voxray/core/error.hpp"
#include "voxray/brickmap/layout.h"
#include "voxray/core/blob.hpp"

namespace voxray {

class top_grid {
protected:
    void init(box3i world, int brick_bits, std::uint32_t payload_bits, std::uint32_t brick_words,
              std::uint32_t occupancy_words, std::uint32_t pages, std::uint32_t bricks) {
        glm::ivec3 e = world.extent();
        for (int a = 0; a < 3; ++a)
            if (std::int64_t(world.min[a]) + e[a] > std::numeric_limits<int>::max())
                fail("brickmap: world box does not fit 32-bit voxel coordinates on axis ", a);
        world_ = world.empty() ? box3i{world.min, world.min} : world;
        brick_bits_ = std::uint32_t(brick_bits);
        payload_bits_ = payload_bits;
        brick_words_ = brick_words;
        occupancy_words_ = occupancy_words;
        std::uint32_t edge = 1u << brick_bits;
        for (int a = 0; a < 3; ++a) {
            cells_[a] = (std::uint32_t(e[a]) + edge - 1) / edge;
            pages_dim_[a] = (cells_[a] + VX_BM_PAGE_MASK) / VX_BM_PAGE_EDGE;
        }
        std::uint64_t table = page_table_words();
        check_blob_size("brickmap page table", VX_BM_HEADER_WORDS + table);
        pages_off_ = std::uint32_t(VX_BM_HEADER_WORDS + table);
        page_used_ = 0;
        words_.clear();
        page_capacity_ = 0;
        brick_capacity_ = 0;
        relayout(std::uint32_t(std::min<std::uint64_t>(pages, std::max<std::uint64_t>(table, 1))), bricks);
        std::fill(words_.begin() + VX_BM_HEADER_WORDS, words_.begin() + pages_off_, VX_BM_EMPTY_PAGE);
    }

    std::uint64_t page_table_words() const { return std::uint64_t(pages_dim_.x) * pages_dim_.y * pages_dim_.z; }

    // Page table word of brick (= top cell) coordinate bc.
    std::uint32_t page_slot(glm::uvec3 bc) const {
        return VX_BM_HEADER_WORDS + VX_BM_PAGE_SLOT(bc.x, bc.y, bc.z, pages_dim_.x, pages_dim_.x * pages_dim_.y);
    }
    std::uint32_t cell_offset(std::uint32_t page, glm::uvec3 bc) const {
        return pages_off_ + page * std::uint32_t(VX_BM_PAGE_WORDS) + VX_BM_PAGE_CELL(bc.x, bc.y, bc.z);
    }

    // Re-lays the blob out with new capacities (never below what is in use: `bricks_in_use`
    // is the pool's high-water mark); moves the brick area.
    void relayout(std::uint32_t pages, std::uint32_t bricks, std::uint32_t bricks_in_use = 0xFFFFFFFFu) {
        pages = std::max(pages, page_used_);
        bricks = std::max(bricks, std::min(brick_capacity_, bricks_in_use));
        std::uint64_t bricks_off = std::uint64_t(pages_off_) + std::uint64_t(pages) * VX_BM_PAGE_WORDS;
        std::uint64_t total = bricks_off + std::uint64_t(bricks) * brick_words_;
        check_words("brickmap", total);
        blob_words next(total, 0u);
        if (!words_.empty()) {
            std::uint64_t keep = std::uint64_t(pages_off_) + std::uint64_t(page_used_) * VX_BM_PAGE_WORDS;
            std::copy(words_.begin(), words_.begin() + keep, next.begin());
            std::copy(words_.begin() + bricks_off_,
                      words_.begin() + bricks_off_ + std::uint64_t(std::min(brick_capacity_, bricks)) * brick_words_,
                      next.begin() + bricks_off);
        }
        words_.swap(next);
        page_capacity_ = pages;
        brick_capacity_ = bricks;
        bricks_off_ = std::uint32_t(bricks_off);
        write_header();
    }

    // Re-lays the blob out for a larger world `w` whose min corner lies whole pages below
    // the old one (so every page keeps its cells and only its page-table slot moves):
    //
    //   old page table (2x1)      new page table (4x2), shift (1, 1)
    //   +---+---+                 +---+---+---+---+
    //   | A | B |        -->      |   | A | B |   |     row y = 1
    //   +---+---+                 +---+---+---+---+
    //                             |   |   |   |   |     row y = 0
    //                             +---+---+---+---+
    //
    // The page pool and brick pool are copied unchanged after the larger table. Returns
    // how far the page pool moved (in words). Strong guarantee: on failure nothing changed.
    std::uint32_t regrid(box3i w) {
        const std::int64_t span = std::int64_t(VX_BM_PAGE_EDGE) << brick_bits_;
        glm::uvec3 shift, cells, dims;
        std::uint32_t edge = 1u << brick_bits_;
        glm::ivec3 e = w.extent();
        for (int a = 0; a < 3; ++a) {
            shift[a] = std::uint32_t((std::int64_t(world_.min[a]) - w.min[a]) / span);
            cells[a] = std::uint32_t((std::uint64_t(e[a]) + edge - 1) / edge);
            dims[a] = (cells[a] + VX_BM_PAGE_MASK) / VX_BM_PAGE_EDGE;
        }
        std::uint64_t table = std::uint64_t(dims.x) * dims.y * dims.z;
        std::uint64_t pages_off = VX_BM_HEADER_WORDS + table;
        std::uint64_t bricks_off = pages_off + std::uint64_t(page_capacity_) * VX_BM_PAGE_WORDS;
        check_words("brickmap (grown world)", bricks_off + std::uint64_t(brick_capacity_) * brick_words_);
        blob_words next(bricks_off + std::uint64_t(brick_capacity_) * brick_words_, 0u);
        std::fill(next.begin() + VX_BM_HEADER_WORDS, next.begin() + std::ptrdiff_t(pages_off), VX_BM_EMPTY_PAGE);
        for (std::uint64_t s = 0, n = page_table_words(); s < n; ++s) {
            std::uint32_t page = words_[VX_BM_HEADER_WORDS + s];
            if (page == VX_BM_EMPTY_PAGE) continue;
            glm::uvec3 pc{std::uint32_t(s % pages_dim_.x), std::uint32_t(s / pages_dim_.x % pages_dim_.y),
                          std::uint32_t(s / pages_dim_.x / pages_dim_.y)};
            pc += shift;
            next[VX_BM_HEADER_WORDS + pc.x + std::uint64_t(dims.x) * (pc.y + std::uint64_t(dims.y) * pc.z)] = page;
        }
        std::copy(words_.begin() + pages_off_, words_.begin() + pages_off_ + std::uint64_t(page_used_) * VX_BM_PAGE_WORDS,
                  next.begin() + std::ptrdiff_t(pages_off));
        std::copy(words_.begin() + bricks_off_, words_.end(), next.begin() + std::ptrdiff_t(bricks_off));
        std::uint32_t moved = std::uint32_t(pages_off) - pages_off_;
        words_.swap(next);
        world_ = w;
        cells_ = cells;
        pages_dim_ = dims;
        pages_off_ = std::uint32_t(pages_off);
        bricks_off_ = std::uint32_t(bricks_off);
        write_header();
        return moved;
    }

    // The blob limit: 8 GiB (core/blob.hpp), or less when the owner asks (options).
    void check_words(const char* what, std::uint64_t words) const {
        check_blob_size(what, words);
        if (words > limit_words_)
            fail(what, " would need a blob of ", words * 4, " bytes, above this brickmap's limit of ", limit_words_ * 4,
                 " bytes (options::max_blob_bytes)");
    }
    // How many bricks fit the limit with `pages` pages of capacity.
    std::uint64_t bricks_fitting(std::uint64_t pages) const {
        std::uint64_t fixed = std::uint64_t(pages_off_) + pages * VX_BM_PAGE_WORDS;
        return fixed >= limit_words_ ? 0 : (limit_words_ - fixed) / brick_words_;
    }

    void write_header() {
        auto* h = words_.data();
        h[VX_BM_HEADER_MAGIC] = VX_BM_MAGIC;
        h[VX_BM_HEADER_VERSION] = VX_BM_VERSION;
        glm::ivec3 e = world_.extent();
        for (int a = 0; a < 3; ++a) {
            h[VX_BM_HEADER_ORIGIN + a] = std::uint32_t(world_.min[a]);
            h[VX_BM_HEADER_EXTENT + a] = std::uint32_t(e[a]);
            h[VX_BM_HEADER_CELLS + a] = cells_[a];
            h[VX_BM_HEADER_PAGES_DIM + a] = pages_dim_[a];
        }
        h[VX_BM_HEADER_BRICK_BITS] = brick_bits_;
        h[VX_BM_HEADER_PAYLOAD_BITS] = payload_bits_;
        h[VX_BM_HEADER_BRICK_WORDS] = brick_words_;
        h[VX_BM_HEADER_OCCUPANCY_WORDS] = occupancy_words_;
        h[VX_BM_HEADER_PAGE_TABLE] = VX_BM_HEADER_WORDS;
        h[VX_BM_HEADER_PAGES] = pages_off_;
        h[VX_BM_HEADER_BRICKS] = bricks_off_;
        h[VX_BM_HEADER_PAGE_CAPACITY] = page_capacity_;
        h[VX_BM_HEADER_BRICK_CAPACITY] = brick_capacity_;
    }

    blob_words words_;
    box3i world_;
    glm::uvec3 cells_{0}, pages_dim_{0};
    std::uint32_t brick_bits_ = 0, payload_bits_ = 0, brick_words_ = 0, occupancy_words_ = 0;
    std::uint32_t pages_off_ = 0, bricks_off_ = 0;
    std::uint32_t page_capacity_ = 0, page_used_ = 0, brick_capacity_ = 0;
    std::uint64_t limit_words_ = max_blob_words - 1;
};

}  // namespace voxray
