// NAADF's construction, edits and field upkeep (declared in naadf/naadf.hpp).
//
// Every edit works chunk by chunk, in batches of chunks:
//   1. in parallel, each chunk is decoded to 16^3 types, edited, and rebuilt with
//      build_chunk (blocks, block fields, groups with their voxel fields);
//   2. in order, each rebuilt chunk is committed: its groups interned (new ones written
//      to the blob), its block array rewritten in place (or taken from the free list),
//      and the old groups released once the batch is in, so unreachable storage is
//      reused;
//   3. each touched page is settled: chunk fields the edit broke are reset to 0, a page
//      that turned empty or uniform collapses, and the page table's fields are checked
//      when a page turned non-empty. refine() grows the reset fields back later.
// The blob is exact after every step a ray can see (all happen under the lock). Step 3,
// refine() and world growth are in detail/upkeep.hpp.
#pragma once
#include <algorithm>
#include <atomic>
#include <bit>
#include <chrono>
#include <cstring>
#include <variant>
#include <vector>

#include "voxray/model/build_threads.hpp"
#include "voxray/naadf/chunk_cells.hpp"
#include "voxray/naadf/chunk_edit.hpp"
#include "voxray/naadf/naadf.hpp"

namespace voxray {

VOXRAY_HOST_INLINE naadf::naadf(const voxel_model& model, naadf_options options) : outside_(options.outside) {
    auto start = std::chrono::steady_clock::now();
    auto built = naadf_detail::build(model, options);
    grid_ = naadf_detail::grid_placement(built.bounds);
    store_.adopt(std::move(built.words), options.headroom);
    store_.limit(options.max_blob_bytes);
    groups_ = std::move(built.groups);
    voxel_count_ = model.voxel_count();
    palette_ = model.palette();
    stale_at_.assign(grid_.page_count, 0);
    touched_flag_.assign(grid_.page_count, 0);
    if (options.distance_fields && options.defer_chunk_fields) {
        for (std::uint64_t slot = 0; slot < grid_.page_count; ++slot)
            if (VX_NA_STATE(*store_.page_cell(slot)) == VX_NA_MIXED) mark_stale(slot, naadf_detail::page_cells().set());
        table_stale_ = true;
    }
    build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

VOXRAY_HOST_INLINE naadf::naadf(naadf_detail::cell_store store, naadf_detail::group_table groups, box3i bounds, std::uint64_t voxels,
                    voxray::palette palette)
    : store_(std::move(store)), groups_(std::move(groups)), grid_(bounds), voxel_count_(voxels), palette_(std::move(palette)) {
    stale_at_.assign(grid_.page_count, 0);
    touched_flag_.assign(grid_.page_count, 0);
}

VOXRAY_HOST_INLINE std::uint32_t naadf::chunk_cell(glm::ivec3 grid) const {
    std::uint32_t page = *store_.page_cell(page_slot(grid));
    if (VX_NA_STATE(page) != VX_NA_MIXED) return VX_NA_STATE(page) == VX_NA_UNIFORM ? page : 0u;
    auto g = glm::uvec3(grid);
    return store_.chunk_array(VX_NA_PAYLOAD(page))[VX_NA_CHUNK_INDEX(g.x, g.y, g.z)];
}

VOXRAY_HOST_INLINE naadf::payload_type naadf::get(glm::ivec3 p) const {
    std::shared_lock lock(locks_.m);
    if (!grid_.bounds.contains(p)) return 0;
    glm::ivec3 grid = p - grid_.origin;
    auto g = glm::uvec3(grid);
    std::uint32_t cell = chunk_cell(grid);
    if (VX_NA_STATE(cell) == VX_NA_MIXED) cell = store_.block_array(VX_NA_PAYLOAD(cell))[VX_NA_BLOCK_INDEX(g.x, g.y, g.z)];
    if (VX_NA_STATE(cell) == VX_NA_UNIFORM) return payload_type(cell & VX_NA_TYPE_MASK);
    if (VX_NA_STATE(cell) != VX_NA_MIXED) return 0;
    std::uint32_t i = VX_NA_VOXEL_INDEX(g.x, g.y, g.z);
    std::uint32_t voxel = store_.group(VX_NA_PAYLOAD(cell))[VX_NA_VOXEL_WORD(i)] >> VX_NA_VOXEL_SHIFT(i);
    return voxel & VX_NA_VOXEL_SOLID ? payload_type(voxel & VX_NA_TYPE_MASK) : 0;
}

VOXRAY_HOST_INLINE std::vector<glm::ivec3> naadf::chunks_of(const box3i& b) const {
    std::vector<glm::ivec3> out;
    if (b.empty()) return out;
    glm::ivec3 lo = (b.min - grid_.origin) >> VX_NA_CHUNK_BITS, hi = (b.max - 1 - grid_.origin) >> VX_NA_CHUNK_BITS;
    for (int z = lo.z; z <= hi.z; ++z)
        for (int y = lo.y; y <= hi.y; ++y)
            for (int x = lo.x; x <= hi.x; ++x) out.push_back(grid_.origin + glm::ivec3(x, y, z) * naadf_detail::chunk_edge);
    return out;
}

VOXRAY_HOST_INLINE void naadf::apply_batch(std::span<const edit> edits, unsigned threads) {
    if (edits.size() >= (1u << 20)) {  // keep the edit index in 20 bits
        apply_batch(edits.first(std::size_t(1) << 19), threads);
        return apply_batch(edits.subspan(std::size_t(1) << 19), threads);
    }
    std::unique_lock lock(locks_.m);
    for (const edit& e : edits)
        if (e.value != 0 && e.op == edit_op::fill) std::visit([&](const auto& r) { make_room(r.exact_bounds()); }, e.region);
    // (chunk, edit) pairs sorted by chunk: each chunk sees its edits in the given order.
    const box3i world = grid_.bounds;
    const glm::ivec3 dim = grid_.pages * (1 << (VX_NA_PAGE_BITS - VX_NA_CHUNK_BITS));
    std::vector<std::uint64_t> keys;
    for (std::size_t i = 0; i < edits.size(); ++i)
        std::visit(
            [&](const auto& r) {
                for (glm::ivec3 c : chunks_of(naadf_detail::intersect(r.bounds(), world))) {
                    if (!r.touches(box3i{c, c + naadf_detail::chunk_edge})) continue;
                    glm::ivec3 k = (c - grid_.origin) >> VX_NA_CHUNK_BITS;
                    std::uint64_t linear = std::uint64_t(k.x) + std::uint64_t(dim.x) * (std::uint64_t(k.y) + std::uint64_t(dim.y) * k.z);
                    keys.push_back(linear << 20 | i);
                }
            },
            edits[i].region);
    std::sort(keys.begin(), keys.end());
    std::vector<std::size_t> starts;
    std::vector<glm::ivec3> chunks;
    for (std::size_t k = 0; k < keys.size(); ++k)
        if (k == 0 || (keys[k] >> 20) != (keys[k - 1] >> 20)) {
            starts.push_back(k);
            std::uint64_t linear = keys[k] >> 20;
            glm::ivec3 c(int(linear % dim.x), int(linear / dim.x % dim.y), int(linear / dim.x / dim.y));
            chunks.push_back(grid_.origin + c * naadf_detail::chunk_edge);
        }
    starts.push_back(keys.size());
    edit_chunks(chunks, threads, [&](std::size_t n, glm::ivec3 origin, voxel_model::chunk& v) {
        bool changed = false;
        for (std::size_t k = starts[n]; k < starts[n + 1]; ++k) {
            const edit& e = edits[keys[k] & 0xFFFFF];
            edit_op op = e.value == 0 ? edit_op::erase : e.op;
            std::visit([&](const auto& r) { changed |= naadf_detail::write_region(r, op, e.value, origin, world, v); }, e.region);
        }
        return changed;
    });
}

VOXRAY_HOST_INLINE void naadf::apply_line(glm::ivec3 a, glm::ivec3 b, int radius, edit_op op, payload_type v, unsigned threads) {
    if (radius > 0) return apply(regions::capsule{a, b, radius}, op, v, threads);
    if (v == 0) op = edit_op::erase;
    std::unique_lock lock(locks_.m);
    if (op == edit_op::fill) make_room(regions::capsule{a, b, 0}.exact_bounds());
    // The line's voxels by chunk: chunk origin, then voxel index in the chunk.
    std::vector<std::pair<glm::ivec3, std::uint16_t>> voxels;
    regions::line_voxels_in(a, b, grid_.bounds, [&](glm::ivec3 p) {
        glm::ivec3 local = (p - grid_.origin) & (naadf_detail::chunk_edge - 1);
        voxels.emplace_back(p - local, std::uint16_t(voxel_model::local_index(local)));
    });
    auto before = [](const auto& x, const auto& y) {
        return std::tie(x.first.z, x.first.y, x.first.x, x.second) < std::tie(y.first.z, y.first.y, y.first.x, y.second);
    };
    std::sort(voxels.begin(), voxels.end(), before);
    std::vector<glm::ivec3> chunks;
    std::vector<std::size_t> starts;
    for (std::size_t i = 0; i < voxels.size(); ++i)
        if (i == 0 || voxels[i].first != voxels[i - 1].first) {
            chunks.push_back(voxels[i].first);
            starts.push_back(i);
        }
    starts.push_back(voxels.size());
    edit_chunks(chunks, threads, [&](std::size_t n, glm::ivec3, voxel_model::chunk& c) {
        bool changed = false;
        for (std::size_t i = starts[n]; i < starts[n + 1]; ++i) {
            std::uint8_t& voxel = c.voxels[voxels[i].second];
            std::uint8_t next = naadf_detail::edited_value(op, v, voxel);
            changed |= next != voxel;
            voxel = next;
        }
        return changed;
    });
}

VOXRAY_HOST_INLINE void naadf::read_box(const box3i& box, payload_type* out) const {
    std::shared_lock lock(locks_.m);
    read_box_locked(box, out);
}

// Chunk by chunk: each decoded once to 16^3 types, then copied a row at a time.
VOXRAY_HOST_INLINE void naadf::read_box_locked(const box3i& box, payload_type* out) const {
    std::fill(out, out + box.volume(), payload_type(0));
    box3i inside = naadf_detail::intersect(box, grid_.bounds);
    glm::ivec3 e = box.extent();
    voxel_model::chunk v;
    for (glm::ivec3 c : chunks_of(inside)) {
        naadf_detail::decode_chunk(chunk_cell(c - grid_.origin), store_.block_array(0), store_.group(0), v);
        box3i q = naadf_detail::intersect({c, c + naadf_detail::chunk_edge}, inside);
        for (int z = q.min.z; z < q.max.z; ++z)
            for (int y = q.min.y; y < q.max.y; ++y) {
                std::size_t row = (std::size_t(z - box.min.z) * e.y + std::size_t(y - box.min.y)) * e.x;
                std::memcpy(out + row + std::size_t(q.min.x - box.min.x),
                            v.voxels.data() + voxel_model::local_index(glm::ivec3(q.min.x, y, z) - c),
                            std::size_t(q.max.x - q.min.x));
            }
    }
}

VOXRAY_HOST_INLINE void naadf::copy_region(box3i src, glm::ivec3 offset, edit_op op, bool replace, unsigned threads) {
    std::unique_lock lock(locks_.m);
    src = naadf_detail::intersect(src, grid_.bounds);
    if (src.empty()) return;
    if (replace || op == edit_op::fill)
        make_room({glm::i64vec3(src.min) + glm::i64vec3(offset), glm::i64vec3(src.max) + glm::i64vec3(offset)});
    // The source first (overlapping copies read the old contents).
    glm::ivec3 ext = src.extent();
    std::vector<std::uint8_t> values(src.volume());
    read_box_locked(src, values.data());
    box3i dst = naadf_detail::intersect({src.min + offset, src.max + offset}, grid_.bounds);
    edit_chunks(chunks_of(dst), threads, [&](std::size_t, glm::ivec3 origin, voxel_model::chunk& c) {
        box3i q = naadf_detail::intersect({origin, origin + naadf_detail::chunk_edge}, dst);
        bool changed = false;
        for (int z = q.min.z; z < q.max.z; ++z)
            for (int y = q.min.y; y < q.max.y; ++y)
                for (int x = q.min.x; x < q.max.x; ++x) {
                    glm::ivec3 s = glm::ivec3(x, y, z) - offset - src.min;
                    std::uint8_t from = values[(std::size_t(s.z) * ext.y + s.y) * ext.x + s.x];
                    if (!replace && from == 0) continue;
                    std::uint8_t& voxel = c.voxels[voxel_model::local_index(glm::ivec3(x, y, z) - origin)];
                    std::uint8_t next = replace ? from : naadf_detail::edited_value(op, from, voxel);
                    changed |= next != voxel;
                    voxel = next;
                }
        return changed;
    });
}

template <class ChunkEdit>
void naadf::edit_chunks(const std::vector<glm::ivec3>& chunks, unsigned threads, ChunkEdit&& chunk_edit) {
    // Batches bound the memory of rebuilt chunks waiting for their commit.
    // Their buffers and the workers' field caches live on between edits.
    constexpr std::size_t batch = 1024;
    std::vector<edited_chunk>& results = scratch_.chunks;
    if (results.size() < std::min(batch, chunks.size())) results.resize(std::min(batch, chunks.size()));
    for (std::size_t begin = 0; begin < chunks.size(); begin += batch) {
        std::size_t n = std::min(batch, chunks.size() - begin);
        std::atomic<std::size_t> next{0};
        // A chunk rebuild costs tens of microseconds: a thread pays off from a few chunks.
        unsigned workers = resolve_build_threads(threads, n / 4);
        while (scratch_.caches.size() < workers) scratch_.caches.push_back(std::make_unique<naadf_detail::field_cache>());
        run_build_threads(workers, [&](unsigned id) {
            naadf_detail::field_cache& cache = *scratch_.caches[id];
            voxel_model::chunk v, old;
            for (;;) {
                std::size_t k = next.fetch_add(1, std::memory_order_relaxed);
                if (k >= n) break;
                edited_chunk& c = results[k];
                c.origin = chunks[begin + k];
                naadf_detail::decode_chunk(chunk_cell(c.origin - grid_.origin), store_.block_array(0), store_.group(0), old);
                v.voxels = old.voxels;
                c.changed = chunk_edit(begin + k, c.origin, v);
                // Only blocks whose voxels differ in the end are rebuilt: erasing a ball and
                // filling it one voxel on leaves its inside as it was.
                std::uint64_t blocks = c.changed ? naadf_detail::changed_blocks(old, v) : 0;
                c.changed = blocks != 0;
                if (!c.changed) continue;
                std::int64_t after = naadf_detail::solid_voxels(v);
                c.delta = after - naadf_detail::solid_voxels(old);
                c.empty = after == 0;
                if (!c.empty) rebuild(c, v, blocks, cache);
            }
        });
        try {
            for (std::size_t k = 0; k < n; ++k)
                if (results[k].changed) commit(results[k]);
        } catch (...) {
            // Growth past the limit: the chunks committed so far stay, and their pages
            // are settled, so the structure is consistent and every field correct.
            finish_batch();
            settle_pages();
            throw;
        }
        finish_batch();
    }
    settle_pages();
}

// Old groups are released only once a batch is committed: a group a rebuild found in the
// table (and so did not give fields) must still be there when its chunk is committed.
VOXRAY_HOST_INLINE void naadf::finish_batch() {
    for (std::uint32_t g : released_) groups_.release(g);
    released_.clear();
}

VOXRAY_HOST_INLINE void naadf::rebuild(edited_chunk& c, const voxel_model::chunk& v, std::uint64_t blocks,
                           naadf_detail::field_cache& cache) const {
    naadf_detail::build_chunk(v, true, c.built, blocks);
    std::size_t groups = c.built.groups.size();
    c.hashes.resize(groups);
    c.fielded.resize(groups);
    // Fields only for groups the table does not hold yet: a known group's words are in
    // the blob already (commit writes only new ones).
    for (std::size_t i = 0; i < groups; ++i) {
        c.hashes[i] = naadf_detail::group_hash(c.built.groups[i]);
        if (groups_.contains(c.built.groups[i], c.hashes[i])) continue;
        c.fielded[i] = c.built.groups[i];
        naadf_detail::add_fields(c.fielded[i].data(), cache);
    }
}

VOXRAY_HOST_INLINE void naadf::touch(std::uint64_t slot, unsigned flags) {
    if (!touched_flag_[slot]) touched_.push_back(slot);
    touched_flag_[slot] |= std::uint8_t(flags);
}

VOXRAY_HOST_INLINE void naadf::open_page(std::uint64_t slot) {
    std::uint32_t page = *store_.page_cell(slot);
    std::uint32_t index = store_.alloc_chunk_array();  // may re-lay the blob out
    std::uint32_t* array = store_.chunk_array(index);
    // The page's chunks as its cell implies: an empty page's fields are its own (in
    // pages); its chunks start with field 0 and regrow.
    std::fill_n(array, VX_NA_CHUNK_ARRAY_WORDS, VX_NA_STATE(page) == VX_NA_UNIFORM ? page : 0u);
    store_.mark(array, VX_NA_CHUNK_ARRAY_WORDS);
    std::uint32_t* cell = store_.page_cell(slot);
    *cell = VX_NA_MIXED_CELL(index);
    store_.mark(cell, 1);
    touch(slot, VX_NA_STATE(page) == VX_NA_EMPTY ? page_was_empty : 0u);
}

VOXRAY_HOST_INLINE void naadf::commit(edited_chunk& c) {
    glm::ivec3 grid = c.origin - grid_.origin;
    auto g = glm::uvec3(grid);
    std::uint64_t slot = page_slot(grid);
    if (VX_NA_STATE(*store_.page_cell(slot)) != VX_NA_MIXED) open_page(slot);
    touch(slot, page_edited);
    const std::uint32_t array = VX_NA_PAYLOAD(*store_.page_cell(slot)), at = VX_NA_CHUNK_INDEX(g.x, g.y, g.z);
    const std::uint32_t old = store_.chunk_array(array)[at];
    // The old chunk's groups are released after the whole batch is committed (see
    // edit_chunks): a group both use keeps its index and its words. Kept blocks keep
    // theirs (only an old mixed chunk has any).
    const std::uint64_t kept = c.empty ? 0 : c.built.kept;
    std::array<std::uint32_t, 64> old_blocks{};
    if (VX_NA_STATE(old) == VX_NA_MIXED) {
        const std::uint32_t* blocks = store_.block_array(VX_NA_PAYLOAD(old));
        std::copy(blocks, blocks + 64, old_blocks.begin());
    }
    std::uint32_t cell = 0;  // empty; its field is reset, refine() grows it
    if (!c.empty && VX_NA_STATE(c.built.cell) == VX_NA_UNIFORM) {
        cell = c.built.cell;
    } else if (!c.empty) {
        // Everything that may grow the blob (and so fail) comes before any reference
        // count changes.
        store_.reserve_groups(groups_.size() + c.built.groups.size());
        std::uint32_t index = VX_NA_STATE(old) == VX_NA_MIXED ? VX_NA_PAYLOAD(old) : store_.alloc_block_array();
        std::array<std::uint32_t, 64> blocks = c.built.blocks;
        for (int i = 0; i < 64; ++i) {
            auto& b = blocks[i];
            if (kept >> i & 1u) {
                b = old_blocks[i];
                continue;
            }
            if (VX_NA_STATE(b) != VX_NA_MIXED) continue;
            std::uint32_t local = VX_NA_PAYLOAD(b);
            auto r = groups_.intern(c.built.groups[local], c.hashes[local]);
            if (r.added) {
                std::uint32_t* words = store_.group(r.index);
                std::copy(c.fielded[local].begin(), c.fielded[local].end(), words);
                store_.mark(words, VX_NA_GROUP_WORDS);
            }
            b = VX_NA_MIXED_CELL(r.index);
        }
        std::uint32_t* words = store_.block_array(index);
        if (!std::equal(blocks.begin(), blocks.end(), words)) {
            std::copy(blocks.begin(), blocks.end(), words);
            store_.mark(words, VX_NA_BLOCK_ARRAY_WORDS);
        }
        cell = VX_NA_MIXED_CELL(index);
    }
    for (int b = 0; b < 64; ++b)
        if (VX_NA_STATE(old_blocks[b]) == VX_NA_MIXED && !(kept >> b & 1u)) released_.push_back(VX_NA_PAYLOAD(old_blocks[b]));
    if (VX_NA_STATE(old) == VX_NA_MIXED && VX_NA_STATE(cell) != VX_NA_MIXED) store_.free_block_array(VX_NA_PAYLOAD(old));
    std::uint32_t* word = store_.chunk_array(array) + at;  // after any re-layout above
    if (*word != cell) {
        *word = cell;
        store_.mark(word, 1);
    }
    bool was_empty = VX_NA_STATE(old) == VX_NA_EMPTY, is_empty = VX_NA_STATE(cell) == VX_NA_EMPTY;
    if (was_empty && !is_empty) touch(slot, chunk_filled);
    if (!was_empty && is_empty) emptied_[slot].set(at);
    voxel_count_ = std::uint64_t(std::int64_t(voxel_count_) + c.delta);
}

}  // namespace voxray
