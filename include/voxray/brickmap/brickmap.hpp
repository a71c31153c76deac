// An editable two-level voxel world: a paged top grid of 32-bit cells (empty, solid with
// one payload, or a brick index) over a growable pool of edge^3 bricks. The data lives in
// the blob words themselves (brickmap/layout.h), so blob() is zero-copy and a
// dirty range is a range of those words.
//
// Threads: set/get/apply may run from many threads at once. Writers hold a shared lock on
// `grow_` (growth of the pool or the page area takes it exclusively and may move the
// brick area), a cell turns into a brick by compare-exchange (a loser gives its brick
// back), and a brick is edited under a spin lock bit in its host-side metadata word:
//
//   meta (host only, one word per brick):
//    31     30       29      28 .. 16   15 .. 0
//   +----+-------+-------+----------+--------------+
//   |lock|pending| dirty |    0     | solid voxels |
//   +----+-------+-------+----------+--------------+
//
// A brick whose count reaches 0 or edge^3 is only *marked* pending; settle() (exclusive,
// run by every region op, take_dirty_ranges() and save) recycles empty bricks and
// collapses uniform ones into solid cells. Freeing only when no writer can hold the
// brick's index is what makes recycling safe without hazard pointers; between settles
// the blob is still valid, just not maximally compact.
//
// Solid cells keep the payload in bits 1..31, so a uint32_t payload >= 2^31 cannot be a
// solid cell: such bricks simply stay bricks. Voxels outside bounds() are never set, so a
// brick that sticks out of the world never collapses.
//
// Bounds: a fill reaching outside bounds() grows the world by default (see
// world_growth.hpp for the policy and options::outside for the alternatives). Growth
// takes the exclusive lock and moves the world's min corner by whole pages, so edits
// name bricks by absolute voxel position and find their top cell under the shared lock.
#pragma once
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <mutex>
#include <shared_mutex>
#include <span>
#include <string_view>
#include <thread>
#include <variant>
#include <vector>

#include "voxray/brickmap/brick_codec.hpp"
#include "voxray/brickmap/brick_pool.hpp"
#include "voxray/sync/change_log.hpp"
#include "voxray/sync/sync_frame.hpp"
#include "voxray/sync/dirty_set.hpp"
#include "voxray/edit/region_shortcuts.hpp"
#include "voxray/edit/regions.hpp"
#include "voxray/brickmap/top_grid.hpp"
#include "voxray/edit/world_growth.hpp"
#include "voxray/core/box.hpp"
#include "voxray/core/error.hpp"
#include "voxray/model/build_threads.hpp"
#include "voxray/model/palette.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/core/blob.hpp"
#include "voxray/core/word_range.hpp"

#define VOXRAY_KERNEL_NAME brickmap
#define VOXRAY_KERNEL_FILE "voxray/brickmap/kernel.h"
#include "voxray/kernels/kernel_tag.inc"

namespace voxray {

template <class Payload, int E>
struct brickmap_io;

template <class Payload = std::uint8_t, int BrickEdge = 8>
class brickmap : private top_grid, public region_shortcuts<brickmap<Payload, BrickEdge>, Payload> {
public:
    using codec = brick_codec<Payload, BrickEdge>;
    using payload_type = Payload;
    static constexpr int brick_edge = BrickEdge;
    static constexpr std::string_view name = "brickmap";
    // The pool's doubling appends bricks and marks only the header (detail/capacity.hpp),
    // so tracers keep the old words on the device (tracer.hpp, grows_in_place).
    static constexpr bool growth_keeps_prefix = true;
    using kernel = kernels::brickmap_kernel;

    struct options {
        std::uint32_t initial_bricks = 64;  // pool capacity before the first growth
        std::uint32_t initial_pages = 1;
        outside_edits outside = outside_edits::grow;  // fills outside bounds(): see world_growth.hpp
        // Spare capacity build() keeps, as a fraction of the bricks and pages it used, so
        // that the first new bricks after a build do not re-lay the blob out (a re-layout
        // makes every tracer receive the whole blob again).
        float build_headroom = 0.25f;
        // The largest blob this map may grow to (at most, and by default, 8 GiB less a
        // word: 32-bit word offsets). Growth fills up to it exactly, not by doubling past it.
        std::uint64_t max_blob_bytes = (max_blob_words - 1) * 4;
    };

    brickmap() : brickmap(box3i{}) {}
    explicit brickmap(box3i world, options opt = {}) : outside_(opt.outside), phase_(world.min) {
        limit_words_ = std::min<std::uint64_t>(opt.max_blob_bytes / 4, max_blob_words - 1);
        top_grid::init(world, codec::bits, codec::payload_bits, codec::words, codec::occupancy_words,
                       std::max(opt.initial_pages, 1u), std::max(opt.initial_bricks, 1u));
        pool_.reset(brick_capacity());
        meta_.assign(brick_capacity(), 0);
        owner_.assign(brick_capacity(), 0);
        dirty_.mark_whole();  // the device has nothing yet
    }
    explicit brickmap(const voxel_model& model, unsigned threads = 0) : brickmap(build(model, threads)) {}

    // Multi-threaded build over the model's chunks; `threads` 0 = all hardware threads.
    static brickmap build(const voxel_model& model, unsigned threads = 0, options opt = {});

    // ---- single voxels (thread-safe) ----
    Payload get(glm::ivec3 p) const {
        std::shared_lock lock(locks_.grow);
        if (!world_.contains(p)) return 0;
        glm::uvec3 q(p - world_.min);
        std::uint32_t co = find_cell(q >> unsigned(codec::bits));
        if (!co) return 0;
        std::uint32_t c = codec::load(words_.data() + co);
        if (!(c & VX_BM_CELL_IS_BRICK)) return Payload(VX_BM_CELL_VALUE(c));
        return codec::get(brick_ptr(VX_BM_CELL_VALUE(c)), local_index(q));
    }
    // The payload of every voxel of `box` (world coordinates) into `out`, x fastest, then y,
    // then z; 0 where empty or outside: the mesher's chunk source (brickmap/read_box.hpp).
    // One top-cell lookup per brick; a solid cell fills its rows at once.
    void read_box(const box3i& box, Payload* out) const {
        std::shared_lock lock(locks_.grow);
        std::fill(out, out + box.volume(), Payload(0));
        box3i in{glm::max(box.min, world_.min), glm::min(box.max, world_.max)};
        if (in.empty()) return;
        constexpr int edge = 1 << codec::bits;
        glm::ivec3 e = box.extent();
        glm::uvec3 first = brick_of(in.min), last = brick_of(in.max - 1);
        for (std::uint32_t bz = first.z; bz <= last.z; ++bz)
            for (std::uint32_t by = first.y; by <= last.y; ++by)
                for (std::uint32_t bx = first.x; bx <= last.x; ++bx) {
                    std::uint32_t co = find_cell({bx, by, bz});
                    std::uint32_t c = co ? codec::load(words_.data() + co) : VX_BM_CELL_EMPTY;
                    if (c == VX_BM_CELL_EMPTY) continue;
                    glm::ivec3 cell = world_.min + glm::ivec3(glm::uvec3(bx, by, bz)) * edge;
                    glm::ivec3 lo = glm::max(cell, in.min), hi = glm::min(cell + edge, in.max);
                    const std::uint32_t* brick = c & VX_BM_CELL_IS_BRICK ? brick_ptr(VX_BM_CELL_VALUE(c)) : nullptr;
                    for (int z = lo.z; z < hi.z; ++z)
                        for (int y = lo.y; y < hi.y; ++y) {
                            Payload* row = out + (std::size_t(z - box.min.z) * e.y + std::size_t(y - box.min.y)) * e.x;
                            Payload* first_voxel = row + (lo.x - box.min.x);
                            auto n = std::uint32_t(hi.x - lo.x);
                            if (!brick) std::fill(first_voxel, first_voxel + n, Payload(VX_BM_CELL_VALUE(c)));
                            else codec::get_run(brick, local_index(glm::uvec3(glm::ivec3(lo.x, y, z) - world_.min)), n, first_voxel);
                        }
                }
    }
    // Sets voxel p to v; 0 erases. Outside bounds(), see options::outside.
    void set(glm::ivec3 p, Payload v) {
        if (v) make_room(regions::box64{glm::i64vec3(p), glm::i64vec3(p) + std::int64_t(1)});
        run r{local_of(p), 1};
        edit_ctx ctx;
        edit_with_growth(p, v ? edit_op::fill : edit_op::erase, v, false, ctx,
                         [&](std::uint32_t* brick) { return codec::write_run(brick, r.first, 1, r.op(v), v); });
    }

    // ---- regions (thread-safe; each call parallelizes over bricks with `threads`) ----
    // fill: every voxel of the region gets `value`; erase: 0; paint: `value` where solid.
    template <class Region>
    void apply(const Region& region, edit_op op, Payload value, unsigned threads = 1);
    // A list of region edits applied in order (see apply_batch).
    struct edit {
        std::variant<regions::box, regions::sphere, regions::capsule> region;
        edit_op op = edit_op::fill;
        Payload value = 0;
    };
    // Same result as apply() of each edit in turn; threads share out bricks, not edits.
    void apply_batch(std::span<const edit> edits, unsigned threads = 1);
    // fill_box, erase_sphere and the like: edit/region_shortcuts.hpp.
    // radius 0: a one-voxel-thick 3D DDA line (regions::line_voxels); else a capsule.
    void apply_line(glm::ivec3 a, glm::ivec3 b, int radius, edit_op op, Payload v, unsigned threads = 1);
    // Copies src to src + offset (overlap allowed: the source is read first).
    // replace = true: the destination becomes exactly the source, empty voxels included;
    // else op says what a solid source voxel does: fill stamps it, erase carves the
    // destination, paint recolours solid destination voxels.
    void copy_region(box3i src, glm::ivec3 offset, edit_op op = edit_op::fill, bool replace = true);

    // ---- maintenance and sync ----
    // Recycles empty bricks and collapses uniform ones (see the top comment).
    void settle() {
        std::unique_lock lock(locks_.grow);
        settle_locked();
    }

    // A consistent view of the blob while other threads edit (sync/sync_frame.hpp).
    using sync_frame = voxray::sync_frame;
    // The blob as it is (no ranges) and its generation: what a new consumer starts from.
    sync_frame snapshot() const {
        std::unique_lock lock(locks_.grow);
        commit_locked();
        return {std::move(lock), words_, {}, log_.generation(), voxel_count()};
    }
    // The blob and the words changed after generation g (settles first). Any number of
    // consumers each keep their own g (tracer::update does).
    sync_frame changes_since(std::uint64_t g) {
        std::unique_lock lock(locks_.grow);
        settle_locked();
        commit_locked();
        return {std::move(lock), words_, log_.since(g, std::uint32_t(words_.size())), log_.generation(), voxel_count()};
    }
    // Word ranges changed since the last take_dirty_ranges() (one consumer; with several,
    // each asks changes_since). A single range covering the whole blob means "upload
    // everything": the blob was re-laid out or resized.
    std::vector<word_range> take_dirty_ranges() {
        auto frame = changes_since(taken_);
        taken_ = frame.generation;
        return std::move(frame.ranges);
    }
    // Whether the next take_dirty_ranges() returns the whole blob.
    bool whole_blob_dirty() const {
        std::shared_lock lock(locks_.grow);  // whole-blob marks and commits take it exclusively
        return dirty_.whole() || log_.whole_since(taken_);
    }
    // Drops unused pool and page capacity; the next growth doubles again.
    void shrink_to_fit() {
        std::unique_lock lock(locks_.grow);
        fit_locked(0.0);
    }
    // Capacity for at least `bricks` bricks and `pages` pages now (one re-layout, so one
    // whole upload now rather than one per growth later).
    void reserve(std::uint32_t bricks, std::uint32_t pages = 0) {
        std::unique_lock lock(locks_.grow);
        pages = std::uint32_t(std::min<std::uint64_t>(pages, std::max<std::uint64_t>(page_table_words(), 1)));
        if (bricks <= brick_capacity() && pages <= page_capacity_) return;
        relayout(std::max(pages, page_capacity_), std::max(bricks, brick_capacity()));
        resize_brick_state();
        dirty_.mark_whole();
    }

    // ---- what every structure exposes ----
    std::span<const std::uint32_t> blob() const { return words_; }
    std::size_t bytes() const { return words_.size() * sizeof(std::uint32_t); }
    // Bytes without unused pool capacity (what a compacted save would need).
    std::size_t used_bytes() const {
        return (std::size_t(bricks_off_ - page_capacity_ * std::uint64_t(VX_BM_PAGE_WORDS)) +
                std::size_t(page_used_) * VX_BM_PAGE_WORDS + std::size_t(pool_.used()) * codec::words) * 4;
    }
    double bytes_per_voxel() const { auto n = voxel_count(); return n ? double(bytes()) / double(n) : 0.0; }
    std::uint64_t voxel_count() const {
        return std::uint64_t(std::atomic_ref<std::int64_t>(const_cast<std::int64_t&>(voxel_count_)).load());
    }
    box3i bounds() const {
        std::shared_lock lock(locks_.grow);
        return world_;
    }
    // Colours and materials of the payload values 1..255 (build() takes the model's;
    // files carry it). Payloads above 255 have no entry.
    voxray::palette palette() const {
        std::shared_lock lock(locks_.grow);
        return palette_;
    }
    void set_palette(const voxray::palette& p) {
        std::unique_lock lock(locks_.grow);
        palette_ = p;
    }
    outside_edits outside_policy() const { return outside_; }
    double build_seconds() const { return build_seconds_; }
    std::uint64_t brick_count() const { return pool_.live(); }
    std::uint64_t free_bricks() const { return pool_.free_in_ring(); }
    std::uint32_t brick_capacity() const { return top_grid::brick_capacity_; }
    std::uint32_t bricks_used() const { return pool_.used(); }  // high-water mark
    std::uint32_t page_count() const { return page_used_; }
    std::uint32_t page_capacity() const { return page_capacity_; }

private:
    friend struct brickmap_io<Payload, BrickEdge>;
    static constexpr std::uint32_t count_mask = 0xFFFFu, dirty_bit = 1u << 29, pending_bit = 1u << 30,
                                   lock_bit = 1u << 31;
    static constexpr std::uint32_t full = codec::voxels;

    struct run {
        std::uint32_t first, n;
        static edit_op op(Payload v) { return v ? edit_op::fill : edit_op::erase; }
    };
    // What one thread changed; merged into the shared sets once per call (flush).
    struct edit_ctx {
        std::vector<std::uint32_t> bricks, words, pending;
        std::int64_t delta = 0;
    };
    enum class status { ok, need_bricks, need_pages };

    // Mutexes are not movable; a copied or moved brickmap gets fresh ones.
    struct locks {
        std::shared_mutex grow;
        std::mutex side;  // dirty_ and pending_
        std::mutex page;  // page creation (rare)
        locks() = default;
        locks(const locks&) {}
        locks& operator=(const locks&) { return *this; }
    };

    // A voxel's index in its brick, from absolute coordinates: the world origin moves by
    // whole pages only, so its alignment to bricks is that of the first origin (phase_).
    std::uint32_t local_of(glm::ivec3 p) const { return local_index(glm::uvec3(p) - glm::uvec3(phase_)); }
    static std::uint32_t local_index(glm::uvec3 q) {
        constexpr std::uint32_t m = BrickEdge - 1;
        return codec::index(q.x & m, q.y & m, q.z & m);
    }
    static bool fits_solid(Payload v) { return std::uint64_t(v) < (std::uint64_t(1) << 31); }
    std::uint32_t* brick_ptr(std::uint32_t b) { return words_.data() + bricks_off_ + std::uint64_t(b) * codec::words; }
    const std::uint32_t* brick_ptr(std::uint32_t b) const {
        return words_.data() + bricks_off_ + std::uint64_t(b) * codec::words;
    }

    std::uint32_t lock_brick(std::uint32_t b) {
        std::atomic_ref<std::uint32_t> m(meta_[b]);
        for (;;) {
            std::uint32_t old = m.fetch_or(lock_bit, std::memory_order_acquire);
            if (!(old & lock_bit)) return old;
            while (m.load(std::memory_order_relaxed) & lock_bit) std::this_thread::yield();
        }
    }
    void unlock_brick(std::uint32_t b, std::uint32_t m) {
        std::atomic_ref<std::uint32_t>(meta_[b]).store(m & ~lock_bit, std::memory_order_release);
    }

    // Publishes a thread's dirty bricks/words, pending bricks and count change. Called with
    // the shared lock held, so settle() and take_dirty_ranges() (exclusive) never miss
    // or race with it; the side mutex orders flushes among themselves.
    void flush(edit_ctx& ctx) {
        if (ctx.delta) std::atomic_ref<std::int64_t>(voxel_count_).fetch_add(ctx.delta);
        ctx.delta = 0;
        if (ctx.bricks.empty() && ctx.words.empty() && ctx.pending.empty()) return;
        std::lock_guard lock(locks_.side);
        dirty_.add_bricks(ctx.bricks);
        dirty_.add_words(ctx.words);
        pending_.insert(pending_.end(), ctx.pending.begin(), ctx.pending.end());
        ctx.bricks.clear();  // keep the capacity: flush runs once per brick in set()/build
        ctx.words.clear();
        ctx.pending.clear();
    }

    // Word offset of the top cell of brick coordinate bc; 0 when its page is absent.
    std::uint32_t find_cell(glm::uvec3 bc) const {
        std::uint32_t page = codec::load(words_.data() + page_slot(bc));
        if (page == VX_BM_EMPTY_PAGE) return 0;
        return cell_offset(page, bc);
    }
    // As find_cell, creating the page; 0 with need = true when the page area is full.
    std::uint32_t make_cell(glm::uvec3 bc, edit_ctx& ctx, bool& need) {
        std::uint32_t slot = page_slot(bc);
        std::atomic_ref<std::uint32_t> entry(words_[slot]);
        std::uint32_t page = entry.load(std::memory_order_acquire);
        if (page == VX_BM_EMPTY_PAGE) {
            std::lock_guard lock(locks_.page);
            page = entry.load(std::memory_order_acquire);
            if (page == VX_BM_EMPTY_PAGE) {
                if (page_used_ == page_capacity_) { need = true; return 0; }
                page = page_used_++;
                entry.store(page, std::memory_order_release);  // the page's cells are zero already
                ctx.words.push_back(slot);
            }
        }
        return cell_offset(page, bc);
    }

    // The core edit of one brick coordinate. `write(brick)` applies the edit to a locked
    // brick and returns the codec result. `uniform`: the edit writes `v` (fill) or 0
    // (erase) or paints `v`, which allows the shortcuts on empty/solid cells; `covered`:
    // it covers every voxel of the brick, so a solid/empty cell can take it directly.
    template <class Write>
    status edit_brick(glm::uvec3 bc, edit_op op, Payload v, bool covered, edit_ctx& ctx, Write&& write,
                      bool uniform = true);

    // edit_brick of the brick holding voxel p under a shared lock, growing the pool
    // (exclusive) and retrying when needed; nothing when p is outside the world.
    template <class Write>
    void edit_with_growth(glm::ivec3 p, edit_op op, Payload v, bool covered, edit_ctx& ctx, Write&& write,
                          bool uniform = true) {
        for (;;) {
            std::shared_lock lock(locks_.grow);
            if (!world_.contains(p)) return flush(ctx);
            status st = edit_brick(brick_of(p), op, v, covered, ctx, write, uniform);
            if (st == status::ok) return flush(ctx);  // under the shared lock, see flush
            std::uint32_t seen = st == status::need_bricks ? top_grid::brick_capacity_ : page_capacity_;
            flush(ctx);  // a snapshot taken while we wait sees counts that match the blob
            lock.unlock();
            grow(st, seen);
        }
    }
    // Capacity and world growth (detail/capacity.hpp); all but make_room run with the
    // exclusive lock held or take it.
    void fit_locked(double headroom);
    void resize_brick_state();
    void make_room(const regions::box64& need);
    void grow(status st, std::uint32_t seen);

    glm::uvec3 brick_of(glm::ivec3 p) const { return glm::uvec3(p - world_.min) >> unsigned(codec::bits); }

    void settle_locked() {
        for (auto b : pending_) {
            std::uint32_t m = meta_[b] & ~pending_bit;
            std::uint32_t n = m & count_mask;
            std::uint32_t* brick = brick_ptr(b);
            Payload v{};
            std::uint32_t cell;
            if (n == 0) cell = 0;  // empty bricks are all-zero words already
            else if (n == full && codec::uniform(brick, v) && fits_solid(v)) cell = VX_BM_SOLID_CELL(std::uint32_t(v));
            else { meta_[b] = m; continue; }
            codec::clear(brick);
            words_[owner_[b]] = cell;
            dirty_.add_word(owner_[b]);
            meta_[b] = m & dirty_bit;
            pool_.recycle(b);
        }
        pending_.clear();
    }

    template <class Region>
    void bricks_of(const Region& region, std::vector<glm::ivec3>& list) const;
    template <class Region>
    void edit_region_brick(const Region& region, edit_op op, Payload value, glm::ivec3 lo, edit_ctx& ctx,
                           std::shared_lock<std::shared_mutex>& lock);

    template <class Body>
    void stop_on_failure(edit_ctx& ctx, std::shared_lock<std::shared_mutex>& lock, std::atomic<std::size_t>& next,
                         std::size_t end, Body&& body);

    template <class Region>
    bool covers(const Region& region, const box3i& bb) const {
        if (bb.min != glm::max(bb.min, world_.min) || bb.max != glm::min(bb.max, world_.max)) return false;
        for (int k = 0; k < 8; ++k) {
            glm::ivec3 p{k & 1 ? bb.max.x - 1 : bb.min.x, k & 2 ? bb.max.y - 1 : bb.min.y,
                         k & 4 ? bb.max.z - 1 : bb.min.z};
            if (!region.contains(p)) return false;
        }
        return true;
    }

    // Moves the dirty set into the change log (exclusive lock held). The dirty bits of
    // meta_ de-duplicate bricks in the set, so they go with it. Sync bookkeeping only,
    // hence callable from const snapshots: meta_, dirty_ and log_ are mutable for it.
    void commit_locked() const {
        for (auto b : dirty_.bricks()) meta_[b] &= ~dirty_bit;
        log_.commit(dirty_, std::uint32_t(words_.size()), bricks_off_, codec::words);
    }

    mutable std::vector<std::uint32_t> meta_;  // per brick, see the diagram
    std::vector<std::uint32_t> owner_; // per brick: word offset of the cell pointing to it
    brick_pool pool_;
    mutable dirty_set dirty_;
    mutable change_log log_;
    std::uint64_t taken_ = 0;  // generation of the last take_dirty_ranges()
    voxray::palette palette_;
    std::vector<std::uint32_t> pending_;
    std::int64_t voxel_count_ = 0;
    double build_seconds_ = 0;
    outside_edits outside_ = outside_edits::grow;
    glm::ivec3 phase_{0};  // the world's min corner at construction (see local_of)
    mutable locks locks_;
};

}  // namespace voxray

#include "voxray/brickmap/detail/capacity.hpp"
#include "voxray/brickmap/detail/edit.hpp"
