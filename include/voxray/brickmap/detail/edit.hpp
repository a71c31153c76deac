// Region edits and the multi-threaded build of brickmap (declared in brickmap.hpp).
//
// Both work brick by brick: the bricks a region may touch are listed, threads take them
// from an atomic counter, and each brick is edited under one lock with whole x runs
// (brick_codec::write_run), so the per-voxel cost is a few bit operations. A shared lock
// is held per worker, not per voxel, and released only to grow the pool.
#pragma once
#include <atomic>
#include <algorithm>
#include <chrono>
#include <span>
#include <variant>
#include <vector>

#include "voxray/brickmap/brickmap.hpp"

namespace voxray {

template <class Payload, int E>
template <class Region>
void brickmap<Payload, E>::bricks_of(const Region& region, std::vector<glm::ivec3>& list) const {
    box3i rb = region.bounds();
    box3i bb{glm::max(rb.min, world_.min), glm::min(rb.max, world_.max)};
    if (bb.empty()) return;
    constexpr unsigned bits = unsigned(codec::bits);
    glm::uvec3 b0 = glm::uvec3(bb.min - world_.min) >> bits, b1 = glm::uvec3(bb.max - 1 - world_.min) >> bits;
    for (unsigned z = b0.z; z <= b1.z; ++z)
        for (unsigned y = b0.y; y <= b1.y; ++y)
            for (unsigned x = b0.x; x <= b1.x; ++x) {
                glm::ivec3 lo = world_.min + glm::ivec3(glm::uvec3(x, y, z) << bits);
                if (region.touches(box3i{lo, lo + E})) list.push_back(lo);
            }
}

// One region edit on the brick whose min corner is voxel lo: x runs of the region inside
// the brick, then one locked edit_brick (growing, with `lock` released, when the pool or
// pages are full). Bricks are named by position: the world may grow while unlocked.
template <class Payload, int E>
template <class Region>
void brickmap<Payload, E>::edit_region_brick(const Region& region, edit_op op, Payload value, glm::ivec3 lo,
                                             edit_ctx& ctx, std::shared_lock<std::shared_mutex>& lock) {
    box3i full_box{lo, lo + E};
    box3i rb = region.bounds();
    box3i q{glm::max(glm::max(full_box.min, rb.min), world_.min), glm::min(glm::min(full_box.max, rb.max), world_.max)};
    if (q.empty()) return;
    run runs[E * E];
    int nr = 0;
    for (int z = q.min.z; z < q.max.z; ++z)
        for (int y = q.min.y; y < q.max.y; ++y) {
            auto [a, b] = region.span(y, z, q.min.x, q.max.x);
            if (a < b)
                runs[nr++] = {codec::index(unsigned(a - lo.x), unsigned(y - lo.y), unsigned(z - lo.z)), unsigned(b - a)};
        }
    if (nr == 0) return;
    bool covered = nr == E * E && covers(region, full_box);
    auto write = [&](std::uint32_t* brick) {
        typename codec::result r;
        for (int i = 0; i < nr; ++i) {
            auto w = codec::write_run(brick, runs[i].first, runs[i].n, op, value);
            r.delta += w.delta;
            r.changed |= w.changed;
        }
        return r;
    };
    for (;;) {
        status st = edit_brick(brick_of(lo), op, value, covered, ctx, write);
        if (st == status::ok) return;
        std::uint32_t seen = st == status::need_bricks ? top_grid::brick_capacity_ : page_capacity_;
        flush(ctx);  // a snapshot taken while we wait sees counts that match the blob
        lock.unlock();
        grow(st, seen);
        lock.lock();
    }
}

// Runs a worker's loop; when it throws (the blob limit, say), the other workers stop at
// their next brick and this one's changes are published before the error goes on, so a
// failed edit leaves the map consistent: whole bricks applied, counts matching the blob.
template <class Payload, int E>
template <class Body>
void brickmap<Payload, E>::stop_on_failure(edit_ctx& ctx, std::shared_lock<std::shared_mutex>& lock,
                                           std::atomic<std::size_t>& next, std::size_t end, Body&& body) {
    try {
        body();
    } catch (...) {
        next.store(end);
        if (!lock.owns_lock()) lock.lock();
        flush(ctx);
        throw;
    }
}

template <class Payload, int E>
template <class Region>
void brickmap<Payload, E>::apply(const Region& region, edit_op op, Payload value, unsigned threads) {
    if (value == 0) op = edit_op::erase;  // fill or paint with 0 = erase (only where solid)
    if (op == edit_op::fill) make_room(region.exact_bounds());
    std::vector<glm::ivec3> list;
    {
        std::shared_lock lock(locks_.grow);
        bricks_of(region, list);
    }
    // Below ~16 bricks a second thread costs more to start than it saves.
    unsigned n = resolve_build_threads(threads, list.size() / 16);
    std::atomic<std::size_t> next{0};
    run_build_threads(n, [&](unsigned) {
        edit_ctx ctx;
        std::shared_lock lock(locks_.grow);
        stop_on_failure(ctx, lock, next, list.size(), [&] {
            for (;;) {
                std::size_t k = next.fetch_add(1, std::memory_order_relaxed);
                if (k >= list.size()) break;
                edit_region_brick(region, op, value, list[k], ctx, lock);
            }
        });
        flush(ctx);  // under the shared lock: no settle or take can see half an edit
        lock.unlock();
    });
    settle();
}

// Many edits at once, in order: the (brick, edit) pairs are sorted by brick, so each
// brick sees its edits in the given order while threads share out the bricks. One
// thread start and one settle per batch instead of per edit: the bouncing-balls case.
template <class Payload, int E>
void brickmap<Payload, E>::apply_batch(std::span<const edit> edits, unsigned threads) {
    if (edits.size() >= (1u << 20)) {  // keep the edit index in 20 bits
        apply_batch(edits.first(std::size_t(1) << 19), threads);
        return apply_batch(edits.subspan(std::size_t(1) << 19), threads);
    }
    for (const edit& e : edits)
        if (e.value != 0 && e.op == edit_op::fill) std::visit([&](const auto& r) { make_room(r.exact_bounds()); }, e.region);
    std::vector<std::uint64_t> keys;
    std::vector<glm::ivec3> list;
    // Keys are relative to the world as it is now and decoded to positions with the same
    // origin: growth by another thread meanwhile moves the origin, not the positions.
    std::shared_lock snapshot_lock(locks_.grow);
    const glm::ivec3 origin = world_.min;
    const glm::uvec3 cells = cells_;
    for (std::size_t i = 0; i < edits.size(); ++i) {
        list.clear();
        std::visit([&](const auto& r) { bricks_of(r, list); }, edits[i].region);
        for (auto lo : list) {
            glm::uvec3 bc = brick_of(lo);
            keys.push_back(((bc.x + std::uint64_t(cells.x) * (bc.y + std::uint64_t(cells.y) * bc.z)) << 20) | i);
        }
    }
    snapshot_lock.unlock();
    std::sort(keys.begin(), keys.end());
    // Group starts: a new brick begins where the key without the edit index changes.
    std::vector<std::size_t> starts;
    for (std::size_t k = 0; k < keys.size(); ++k)
        if (k == 0 || (keys[k] >> 20) != (keys[k - 1] >> 20)) starts.push_back(k);
    starts.push_back(keys.size());
    std::size_t groups = starts.size() - 1;
    unsigned n = resolve_build_threads(threads, groups / 16);
    std::atomic<std::size_t> next{0};
    run_build_threads(n, [&](unsigned) {
        edit_ctx ctx;
        std::shared_lock lock(locks_.grow);
        stop_on_failure(ctx, lock, next, groups, [&] {
            for (;;) {
                std::size_t g = next.fetch_add(1, std::memory_order_relaxed);
                if (g >= groups) break;
                std::uint64_t cell = keys[starts[g]] >> 20;
                glm::uvec3 bc(std::uint32_t(cell % cells.x), std::uint32_t(cell / cells.x % cells.y),
                              std::uint32_t(cell / cells.x / cells.y));
                glm::ivec3 lo = origin + glm::ivec3(bc << unsigned(codec::bits));
                for (std::size_t k = starts[g]; k < starts[g + 1]; ++k) {
                    const edit& e = edits[keys[k] & 0xFFFFF];
                    edit_op op = e.value == 0 ? edit_op::erase : e.op;
                    std::visit([&](const auto& r) { edit_region_brick(r, op, e.value, lo, ctx, lock); }, e.region);
                }
            }
        });
        flush(ctx);  // under the shared lock: no settle or take can see half an edit
        lock.unlock();
    });
    settle();
}

template <class Payload, int E>
void brickmap<Payload, E>::apply_line(glm::ivec3 a, glm::ivec3 b, int radius, edit_op op, Payload v,
                                      unsigned threads) {
    if (radius > 0) return apply(regions::capsule{a, b, radius}, op, v, threads);
    if (v == 0) op = edit_op::erase;
    if (op == edit_op::fill) make_room(regions::capsule{a, b, 0}.exact_bounds());
    edit_ctx ctx;
    regions::line_voxels_in(a, b, bounds(), [&](glm::ivec3 p) {
        std::uint32_t i = local_of(p);
        edit_with_growth(p, op, v, false, ctx,
                         [&](std::uint32_t* brick) { return codec::write_run(brick, i, 1, op, v); });
    });
    settle();
}

template <class Payload, int E>
void brickmap<Payload, E>::copy_region(box3i src, glm::ivec3 offset, edit_op op, bool replace) {
    box3i world = bounds();
    src = box3i{glm::max(src.min, world.min), glm::min(src.max, world.max)};
    if (src.empty()) return;
    if (replace || op == edit_op::fill)
        make_room({glm::i64vec3(src.min) + glm::i64vec3(offset), glm::i64vec3(src.max) + glm::i64vec3(offset)});
    glm::ivec3 ext = src.extent();
    std::vector<Payload> values(src.volume());
    std::size_t k = 0;
    for (int z = src.min.z; z < src.max.z; ++z)
        for (int y = src.min.y; y < src.max.y; ++y)
            for (int x = src.min.x; x < src.max.x; ++x) values[k++] = get({x, y, z});
    edit_ctx ctx;
    for (int z = 0; z < ext.z; ++z)
        for (int y = 0; y < ext.y; ++y)
            for (int x = 0; x < ext.x; ++x) {
                glm::ivec3 p = src.min + glm::ivec3(x, y, z) + offset;
                Payload s = values[(std::size_t(z) * ext.y + y) * ext.x + x];
                edit_op o = replace ? (s ? edit_op::fill : edit_op::erase) : op;
                if (!replace && s == 0) continue;
                Payload v = o == edit_op::erase ? Payload(0) : s;
                std::uint32_t i = local_of(p);
                edit_with_growth(p, o, v, false, ctx,
                                 [&](std::uint32_t* brick) { return codec::write_run(brick, i, 1, o, v); });
            }
    settle();
}

template <class Payload, int E>
brickmap<Payload, E> brickmap<Payload, E>::build(const voxel_model& model, unsigned threads, options opt) {
    auto start = std::chrono::steady_clock::now();
    std::vector<std::pair<glm::ivec3, const voxel_model::chunk*>> chunks;
    chunks.reserve(model.chunk_count());
    model.for_each_chunk([&](glm::ivec3 o, const voxel_model::chunk& c) { chunks.emplace_back(o, &c); });
    constexpr std::uint64_t per_chunk = (16 / E) * (16 / E) * (16 / E);
    opt.initial_bricks = std::uint32_t(std::clamp<std::uint64_t>(chunks.size() * per_chunk, opt.initial_bricks, 1u << 24));
    opt.initial_pages = std::max<std::uint32_t>(opt.initial_pages, std::uint32_t(chunks.size() / 64 + 1));
    brickmap m(model.bounds(), opt);
    constexpr unsigned bits = unsigned(codec::bits);
    unsigned n = resolve_build_threads(threads, chunks.size() / 8);
    std::atomic<std::size_t> next{0};
    run_build_threads(n, [&](unsigned) {
        edit_ctx ctx;
        for (;;) {
            std::size_t k = next.fetch_add(1, std::memory_order_relaxed);
            if (k >= chunks.size()) break;
            // Plain variables, not a structured binding: the lambda below captures `chunk`,
            // which clang before 16 rejects for bindings.
            glm::ivec3 origin = chunks[k].first;
            const voxel_model::chunk* chunk = chunks[k].second;
            // Chunks are 16-aligned in world coordinates, the world box is not: q0 may be
            // negative by up to 15, but every solid voxel lies inside the world.
            glm::ivec3 q0 = origin - m.world_.min;
            glm::ivec3 last = glm::min(q0 + 15, m.world_.extent() - 1);
            glm::uvec3 lo = glm::uvec3(glm::max(q0, glm::ivec3(0))) >> bits, hi = glm::uvec3(last) >> bits;
            for (unsigned bz = lo.z; bz <= hi.z; ++bz)
                for (unsigned by = lo.y; by <= hi.y; ++by)
                    for (unsigned bx = lo.x; bx <= hi.x; ++bx) {
                        glm::uvec3 bc(bx, by, bz);
                        // The chunk's voxels inside this brick, in chunk-local coordinates.
                        glm::ivec3 a = glm::max(glm::ivec3(bc << bits) - q0, glm::ivec3(0));
                        glm::ivec3 b = glm::min(glm::ivec3((bc + 1u) << bits) - q0, glm::ivec3(16));
                        bool any = false;
                        for (int z = a.z; z < b.z && !any; ++z)
                            for (int y = a.y; y < b.y && !any; ++y)
                                for (int x = a.x; x < b.x; ++x)
                                    if (chunk->voxels[x | (y << 4) | (z << 8)]) { any = true; break; }
                        if (!any) continue;
                        auto write = [&](std::uint32_t* brick) {
                            typename codec::result r;
                            for (int z = a.z; z < b.z; ++z)
                                for (int y = a.y; y < b.y; ++y)
                                    for (int x = a.x; x < b.x; ++x) {
                                        auto v = chunk->voxels[x | (y << 4) | (z << 8)];
                                        if (!v) continue;
                                        glm::uvec3 q(q0 + glm::ivec3(x, y, z));
                                        auto w = codec::write_run(brick, local_index(q), 1, edit_op::fill, Payload(v));
                                        r.delta += w.delta;
                                        r.changed |= w.changed;
                                    }
                            return r;
                        };
                        glm::ivec3 corner = m.world_.min + glm::ivec3(bc << bits);
                        m.edit_with_growth(corner, edit_op::fill, 1, false, ctx, write, false);
                    }
        }
    });
    m.settle();
    {
        std::unique_lock lock(m.locks_.grow);
        m.fit_locked(std::max(0.0, double(opt.build_headroom)));
    }
    m.dirty_.clear();
    m.dirty_.mark_whole();
    for (auto& w : m.meta_) w &= ~dirty_bit;
    m.palette_ = model.palette();
    m.build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return m;
}

}  // namespace voxray
