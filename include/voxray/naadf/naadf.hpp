// NAADF: nested cells (page, chunk, block, voxel) whose empty cells carry axis-aligned
// distance fields, so a ray crosses empty space in cuboid-sized moves (the NAADF paper,
// sections 3.1-3.5; layout in naadf/layout.h, traversal in naadf/kernel.h). Voxel groups
// are deduplicated by hash, uniform blocks and chunks collapse, and the top level is a
// table of pages, so a sparse 16384^3 world costs megabytes.
//
// Editable with the brickmap's vocabulary (set, regions, batches, lines, copies; fill,
// erase, paint), from any thread. Edits work chunk by chunk (naadf/detail/edit.hpp): an
// edited chunk is decoded, changed, and rebuilt with its block and voxel fields, its
// groups re-interned (unused ones freed for reuse); chunk and page fields that an edit
// breaks are reset to 0 at once (naadf/field_repair.hpp) and grown back by refine().
//
// Threads: edits, refine() and the sync calls take the structure's lock exclusively
// (one edit at a time, each spread over `threads` worker threads); get() and the
// read-only calls share it. Tracers take consistent frames (snapshot, changes_since).
#pragma once
#include <chrono>
#include <cstdint>
#include <memory>
#include <mutex>
#include <shared_mutex>
#include <span>
#include <string_view>
#include <unordered_map>
#include <variant>
#include <vector>

#include "voxray/core/blob.hpp"
#include "voxray/core/box.hpp"
#include "voxray/core/word_range.hpp"
#include "voxray/edit/edit_op.hpp"
#include "voxray/edit/region_shortcuts.hpp"
#include "voxray/edit/regions.hpp"
#include "voxray/model/palette.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/naadf/builder.hpp"
#include "voxray/naadf/cell_store.hpp"
#include "voxray/naadf/field_repair.hpp"
#include "voxray/sync/change_log.hpp"
#include "voxray/sync/sync_frame.hpp"

#define VOXRAY_KERNEL_NAME naadf
#define VOXRAY_KERNEL_FILE "voxray/naadf/kernel.h"
#include "voxray/kernels/kernel_tag.inc"

namespace voxray {

struct naadf_io;

// How far refine() has come: pages whose chunk fields still wait to grow, and whether
// the page table's fields do.
struct naadf_refine_progress {
    std::size_t pages_left = 0;
    bool table_left = false;
    bool done() const { return pages_left == 0 && !table_left; }
};

class naadf : public region_shortcuts<naadf, std::uint8_t> {
public:
    static constexpr std::string_view name = "naadf";
    using kernel = kernels::naadf_kernel;
    using payload_type = std::uint8_t;
    using options = naadf_options;

    // One region edit of a batch (the brickmap's, so tools hand both the same list).
    struct edit {
        std::variant<regions::box, regions::sphere, regions::capsule> region;
        edit_op op = edit_op::fill;
        payload_type value = 0;
    };

    naadf() : naadf(voxel_model{}) {}
    explicit naadf(const voxel_model& model, naadf_options options = {});

    // ---- single voxels (thread-safe) ----
    payload_type get(glm::ivec3 p) const;
    // Sets voxel p to v; 0 erases. Outside bounds(), see options::outside.
    void set(glm::ivec3 p, payload_type v) {
        edit e{regions::box{{p, p + 1}}, v ? edit_op::fill : edit_op::erase, v};
        apply_batch(std::span(&e, 1));
    }

    // ---- regions (thread-safe; `threads` workers share out the edited chunks) ----
    // fill: every voxel of the region gets `value`; erase: 0; paint: `value` where solid.
    template <class Region>
    void apply(const Region& region, edit_op op, payload_type value, unsigned threads = 1) {
        edit e{region, op, value};
        apply_batch(std::span(&e, 1), threads);
    }
    // The edits in order, as apply() of each in turn; each chunk is rebuilt once.
    void apply_batch(std::span<const edit> edits, unsigned threads = 1);
    // fill_box, erase_sphere and the like: edit/region_shortcuts.hpp.
    // radius 0: a one-voxel-thick 3D DDA line (regions::line_voxels); else a capsule.
    void apply_line(glm::ivec3 a, glm::ivec3 b, int radius, edit_op op, payload_type v, unsigned threads = 1);
    // Copies src to src + offset (overlap allowed: the source is read first). replace:
    // the destination becomes exactly the source, empty voxels included; else op says
    // what a solid source voxel does (fill stamps it, erase carves, paint recolours).
    void copy_region(box3i src, glm::ivec3 offset, edit_op op = edit_op::fill, bool replace = true, unsigned threads = 1);

    // ---- distance fields ----
    // Grows the chunk fields of up to `budget` pages that edits (or a build with
    // defer_chunk_fields) left short, then the page table's (one more unit of budget);
    // resumable, and the structure is exact before, during and after. `threads` share out
    // the pages. Returns what is left.
    naadf_refine_progress refine(std::size_t budget = SIZE_MAX, unsigned threads = 1);
    naadf_refine_progress refine_progress() const {
        std::shared_lock lock(locks_.m);
        return {stale_.size(), table_stale_};
    }

    // ---- sync (the brickmap's interface; see tracer.hpp) ----
    using sync_frame = voxray::sync_frame;  // sync/sync_frame.hpp
    sync_frame snapshot() const {
        std::unique_lock lock(locks_.m);
        commit_locked();
        return {std::move(lock), store_.blob(), {}, log_.generation(), voxel_count_};
    }
    sync_frame changes_since(std::uint64_t g) {
        std::unique_lock lock(locks_.m);
        commit_locked();
        auto words = std::uint32_t(store_.blob().size());
        return {std::move(lock), store_.blob(), log_.since(g, words), log_.generation(), voxel_count_};
    }
    std::vector<word_range> take_dirty_ranges() {
        auto frame = changes_since(taken_);
        taken_ = frame.generation;
        return std::move(frame.ranges);
    }

    // ---- queries ----
    // The blob as it is (not a consistent frame while other threads edit: use snapshot()).
    std::span<const std::uint32_t> blob() const { return store_.blob(); }
    std::size_t bytes() const { return blob().size() * sizeof(std::uint32_t); }
    box3i bounds() const {
        std::shared_lock lock(locks_.m);
        return grid_.bounds;
    }
    std::uint64_t voxel_count() const {
        std::shared_lock lock(locks_.m);
        return voxel_count_;
    }
    // The payload of every voxel of `box` (world coordinates) into `out`, x fastest, then y,
    // then z; 0 where empty or outside: the mesher's chunk source (naadf/read_box.hpp).
    void read_box(const box3i& box, payload_type* out) const;
    double build_seconds() const { return build_seconds_; }
    // Figures of the structure as it is now (arrays and groups in use).
    naadf_stats stats() const;
    const voxray::palette& palette() const { return palette_; }
    void set_palette(const voxray::palette& p) { palette_ = p; }

private:
    friend struct naadf_io;
    // One chunk between its parallel rebuild and its commit.
    struct edited_chunk {
        glm::ivec3 origin{0};  // world position of its voxel (0,0,0): a multiple of 16
        bool changed = false;
        bool empty = false;
        std::int64_t delta = 0;  // solid voxels gained
        naadf_detail::built_chunk built;
        std::vector<std::uint32_t> hashes;                // per group of built
        std::vector<naadf_detail::voxel_group> fielded;   // per group: as the blob holds it
    };

    // Mutexes are not movable; a moved naadf gets a fresh one.
    struct locks {
        mutable std::shared_mutex m;
        locks() = default;
        locks(const locks&) {}
        locks& operator=(const locks&) { return *this; }
    };

    naadf(naadf_detail::cell_store store, naadf_detail::group_table groups, box3i bounds, std::uint64_t voxels,
          voxray::palette palette);

    // Chunk edits (detail/edit.hpp).
    template <class ChunkEdit>
    void edit_chunks(const std::vector<glm::ivec3>& chunks, unsigned threads, ChunkEdit&& chunk_edit);
    void rebuild(edited_chunk& c, const voxel_model::chunk& v, std::uint64_t blocks, naadf_detail::field_cache& cache) const;
    void commit(edited_chunk& c);
    void finish_batch();
    void open_page(std::uint64_t slot);
    void touch(std::uint64_t slot, unsigned flags);
    void settle_pages();
    void make_room(const regions::box64& need);
    void regrid(const box3i& world);
    std::vector<glm::ivec3> chunks_of(const box3i& b) const;

    std::uint32_t chunk_cell(glm::ivec3 grid) const;
    void read_box_locked(const box3i& box, payload_type* out) const;  // read_box under a lock held
    std::uint64_t page_slot(glm::ivec3 grid) const {
        auto g = glm::uvec3(grid);
        return VX_NA_PAGE_SLOT(std::uint64_t(g.x), std::uint64_t(g.y), std::uint64_t(g.z), std::uint64_t(grid_.pages.x),
                               std::uint64_t(grid_.pages.x) * grid_.pages.y);
    }
    // Chunks of page `slot` whose fields refine() should regrow.
    void mark_stale(std::uint64_t slot, const naadf_detail::page_cells& cells) {
        if (stale_at_[slot]) {
            stale_[stale_at_[slot] - 1].cells |= cells;
            return;
        }
        stale_.push_back({slot, cells});
        stale_at_[slot] = std::uint32_t(stale_.size());
    }
    void commit_locked() const { log_.commit(store_.dirty(), std::uint32_t(store_.blob().size()), 0, 0); }

    locks locks_;
    naadf_detail::cell_store store_;
    naadf_detail::group_table groups_;
    naadf_detail::grid_placement grid_{box3i{}};
    outside_edits outside_ = outside_edits::grow;
    std::uint64_t voxel_count_ = 0;
    voxray::palette palette_;
    double build_seconds_ = 0;
    // Pages whose chunk fields refine() should grow (which chunks), and the page table's.
    struct stale_page {
        std::uint64_t slot;
        naadf_detail::page_cells cells;
    };
    std::vector<stale_page> stale_;
    std::vector<std::uint32_t> stale_at_;  // per page slot: its index in stale_ + 1, or 0
    bool table_stale_ = false;
    std::unordered_map<std::uint64_t, naadf_detail::page_cells> emptied_;  // chunks the current edit emptied
    // Pages the current edit touched, and what happened to them.
    enum : unsigned { page_edited = 1, chunk_filled = 2, page_was_empty = 4 };
    std::vector<std::uint64_t> touched_;
    std::vector<std::uint8_t> touched_flag_;
    std::vector<std::uint32_t> released_;  // groups the current edit batch stopped using
    // Kept between edits: rebuilt chunks waiting for their commit, and each worker's
    // cache of voxel fields. A copied or moved naadf starts with none.
    struct edit_scratch {
        std::vector<edited_chunk> chunks;
        std::vector<std::unique_ptr<naadf_detail::field_cache>> caches;
        edit_scratch() = default;
        edit_scratch(const edit_scratch&) {}
        edit_scratch& operator=(const edit_scratch&) { return *this; }
    };
    edit_scratch scratch_;
    mutable change_log log_;
    std::uint64_t taken_ = 0;
};

}  // namespace voxray

// The out-of-line members: here, or compiled once in voxray::kernels (core/host_code.hpp).
#include "voxray/core/host_code.hpp"
#if VOXRAY_HOST_DEFINITIONS
#include "voxray/naadf/detail/edit.hpp"
#include "voxray/naadf/detail/upkeep.hpp"
#endif
