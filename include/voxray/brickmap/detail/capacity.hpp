// The core of brickmap's edits and its capacity (declared in brickmap.hpp): edit_brick
// turns cells into bricks and asks for growth when the pool or pages are full; the pool and page area grow by
// doubling up to the blob limit (the last growth takes exactly what still fits, so the
// documented 8 GiB holds), build() keeps headroom, and fills outside the world grow it
// (world_growth.hpp). Every re-layout marks the whole blob dirty (the brick area moves),
// except the pool's doubling, which only appends bricks: it marks the header.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <shared_mutex>

#include "voxray/brickmap/brickmap.hpp"

namespace voxray {

// The core edit of one brick coordinate (see the declaration in brickmap.hpp).
template <class Payload, int E>
template <class Write>
typename brickmap<Payload, E>::status brickmap<Payload, E>::edit_brick(glm::uvec3 bc, edit_op op, Payload v, bool covered,
                                                                      edit_ctx& ctx, Write&& write, bool uniform) {
    bool need = false;
    std::uint32_t co = op == edit_op::fill ? make_cell(bc, ctx, need) : find_cell(bc);
    if (!co) return need ? status::need_pages : status::ok;
    std::atomic_ref<std::uint32_t> cell(words_[co]);
    for (;;) {
        std::uint32_t c = cell.load(std::memory_order_acquire);
        if (c & VX_BM_CELL_IS_BRICK) {
            std::uint32_t b = VX_BM_CELL_VALUE(c);
            std::uint32_t m = lock_brick(b);
            typename codec::result r = write(brick_ptr(b));
            std::uint32_t n = (m & count_mask) + std::uint32_t(r.delta);
            m = (m & ~count_mask) | n;
            if (r.changed && !(m & dirty_bit)) { m |= dirty_bit; ctx.bricks.push_back(b); }
            if ((n == 0 || n == full) && !(m & pending_bit)) { m |= pending_bit; ctx.pending.push_back(b); }
            ctx.delta += r.delta;
            unlock_brick(b, m);
            return status::ok;
        }
        auto s = Payload(VX_BM_CELL_VALUE(c));
        if (s == 0 && op != edit_op::fill) return status::ok;
        if (uniform && s != 0 && op != edit_op::erase && s == v) return status::ok;
        if (uniform && covered && (op == edit_op::erase || fits_solid(v))) {
            std::uint32_t nc = op == edit_op::erase ? 0u : VX_BM_SOLID_CELL(std::uint32_t(v));
            if (cell.compare_exchange_strong(c, nc, std::memory_order_acq_rel)) {
                ctx.words.push_back(co);
                ctx.delta += std::int64_t(full) * ((nc ? 1 : 0) - (c ? 1 : 0));
                return status::ok;
            }
            continue;
        }
        std::uint32_t b = pool_.allocate();
        if (b == brick_pool::none) return status::need_bricks;
        std::uint32_t* brick = brick_ptr(b);
        if (s) codec::fill_solid(brick, s);
        std::atomic_ref<std::uint32_t> meta(meta_[b]);  // private until the cell is published
        meta.store((meta.load(std::memory_order_relaxed) & dirty_bit) | (s ? full : 0u), std::memory_order_relaxed);
        if (!cell.compare_exchange_strong(c, VX_BM_BRICK_CELL(b), std::memory_order_acq_rel)) {
            if (s) codec::clear(brick);
            meta.store(meta.load(std::memory_order_relaxed) & dirty_bit, std::memory_order_relaxed);
            pool_.recycle(b);
            continue;
        }
        owner_[b] = co;
        ctx.words.push_back(co);
        // The whole brick is new on the device: make sure it is uploaded.
        std::uint32_t m = lock_brick(b);
        if (!(m & dirty_bit)) { m |= dirty_bit; ctx.bricks.push_back(b); }
        unlock_brick(b, m);
    }
}

// Capacity to what is used plus `headroom` of it (exclusive lock held).
template <class Payload, int E>
void brickmap<Payload, E>::fit_locked(double headroom) {
    std::uint32_t used = std::max(pool_.used(), 1u);
    std::uint64_t bricks = used + std::uint64_t(double(used) * headroom);
    std::uint64_t pages = page_used_ + std::uint64_t(std::ceil(double(page_used_) * headroom));
    pages = std::clamp<std::uint64_t>(pages, std::max(page_used_, 1u), std::max<std::uint64_t>(page_table_words(), 1));
    bricks = std::min({bricks, std::uint64_t(1) << 31, std::max<std::uint64_t>(bricks_fitting(pages), used)});
    relayout(std::uint32_t(pages), std::uint32_t(bricks), used);
    resize_brick_state();
    dirty_.mark_whole();
}

template <class Payload, int E>
void brickmap<Payload, E>::resize_brick_state() {
    if (top_grid::brick_capacity_ > pool_.capacity()) pool_.grow_to(top_grid::brick_capacity_);
    else pool_.shrink_to(top_grid::brick_capacity_);
    meta_.resize(top_grid::brick_capacity_, 0);
    owner_.resize(top_grid::brick_capacity_, 0);
}

// Makes bounds() hold `need` before a fill, per outside_ (world_growth.hpp).
template <class Payload, int E>
void brickmap<Payload, E>::make_room(const regions::box64& need) {
    if (outside_ == outside_edits::clip) return;
    {
        std::shared_lock lock(locks_.grow);
        if (need.inside(world_)) return;
    }
    std::unique_lock lock(locks_.grow);
    if (need.inside(world_)) return;  // another thread grew it
    if (outside_ == outside_edits::fail) world_growth::refuse(world_, need);
    box3i w = world_growth::grown(world_, need, std::int64_t(VX_BM_PAGE_EDGE) << codec::bits);
    std::uint32_t moved = regrid(w);
    for (auto& o : owner_) o += moved;  // cells moved with the page pool
    dirty_.mark_whole();
}

template <class Payload, int E>
void brickmap<Payload, E>::grow(status st, std::uint32_t seen) {
    std::unique_lock lock(locks_.grow);
    if (st == status::need_bricks) {
        if (top_grid::brick_capacity_ != seen) return;  // another thread grew it
        // Doubling, but never past the limit: the last growth takes what still fits.
        std::uint64_t cap = std::min({std::max<std::uint64_t>(2ull * seen, 16), std::uint64_t(1) << 31,
                                      bricks_fitting(page_capacity_)});
        if (cap <= seen)
            fail("brickmap: brick ", seen + 1, " does not fit: ", seen, " bricks of ", codec::words * 4,
                 " bytes already fill the blob up to its limit of ", limit_words_ * 4,
                 " bytes (options::max_blob_bytes; 8 GiB at most)");
        relayout(page_capacity_, std::uint32_t(cap));
        resize_brick_state();
        // The brick area grew at the end of the blob and nothing else moved: only the header
        // changed below the old size (growth_keeps_prefix), and the new bricks are zero.
        dirty_.add_range({0, VX_BM_HEADER_WORDS});
        return;
    } else {
        if (page_capacity_ != seen) return;
        std::uint64_t cap = std::min<std::uint64_t>(2ull * seen, page_table_words());
        std::uint64_t brick_words = std::uint64_t(top_grid::brick_capacity_) * codec::words;
        std::uint64_t fixed = std::uint64_t(pages_off_) + brick_words;
        std::uint64_t fitting = fixed >= limit_words_ ? 0 : (limit_words_ - fixed) / VX_BM_PAGE_WORDS;
        cap = std::min(cap, fitting);
        if (cap <= seen)
            fail("brickmap: page ", seen + 1, " does not fit: the blob is at its limit of ", limit_words_ * 4,
                 " bytes (options::max_blob_bytes; 8 GiB at most)");
        relayout(std::uint32_t(cap), top_grid::brick_capacity_);
    }
    dirty_.mark_whole();
}

}  // namespace voxray
