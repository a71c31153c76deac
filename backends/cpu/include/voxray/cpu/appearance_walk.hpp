// The compositing walk (appearance/walk.inc) on the CPU, for any structure kernel: many
// rays on a thread pool, each blended front to back through its voxels' appearance records.
// The same source the GPUs run. With voxray::cpu (the default) the walk goes in rounds over
// a batch of rays: the closest hits of every ray still walking, on the SIMD stream the
// tracer uses, then each ray's visit (appearance/walk_visit.h), its compact records'
// samples on SIMD lanes too (cpu/appearance_samples.hpp). With voxray::cpu_scalar each ray
// walks alone on the scalar lanes. Both give the same pixels bit for bit: the SIMD lanes
// run the scalar kernel's code.
//
//   voxray::appearance_walker<voxray::kernels::dense_grid_kernel> walker(blob, table);
//   std::vector<voxray::appearance_pixel> out = walker.walk(rays, light);
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#if !defined(VOXRAY_LINKED_CPU)
#error "voxray/cpu/appearance_walk.hpp needs voxray::cpu (the scalar lanes the walk runs on): link it"
#endif
#include "voxray/appearance/walk_inputs.hpp"
#include "voxray/core/error.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/cpu/appearance_kernels.hpp"
#include "voxray/cpu/appearance_samples.hpp"
#include "voxray/cpu/cpu_backend.hpp"

namespace voxray::kernels::scalar {
#define VX_APP_WALK_NAME vx_app_walk
#define VX_APP_WALK_PREFIX template <class Kernel>
#define VX_APP_WALK_TRACE(b, r) kernel_lanes<Kernel>::template trace<VX_MODE_CLOSEST>(b, r)
#include "voxray/appearance/walk.inc"
}  // namespace voxray::kernels::scalar

namespace voxray {

template <class Kernel, class Backend = cpu>
class appearance_walker {
public:
    static constexpr const char* backend = Backend::name;

    // `blob` is the structure's words, `table` the appearance of its voxels (its rows in the
    // ordinal index's order); both are copied. `threads` 0: one per hardware thread.
    appearance_walker(std::vector<std::uint32_t> blob, const appearance::appearance_table& table,
                      unsigned threads = 0)
        : appearance_walker(std::move(blob), table, cpu_options{.threads = threads}) {}
    // The same with the tracer's CPU options (threads or a shared pool, the SIMD width).
    appearance_walker(std::vector<std::uint32_t> blob, const appearance::appearance_table& table, cpu_options options)
        : blob_(std::move(blob)), words_(table), engine_(borrowing(std::move(options))) {
        engine_.upload(blob_);  // borrowed: blob_'s buffer stays where it is when the walker moves
    }

    // Rays' directions must be unit vectors (records are evaluated for them).
    std::vector<appearance_pixel> walk(std::span<const ray> rays, const appearance_light& light) const {
        std::vector<appearance_pixel> out(rays.size());
        const std::uint32_t shadows_at = words_.shadows.at_for(light);
        std::size_t batches = (rays.size() + batch - 1) / batch;
        engine_.pool()->parallel_for(batches, [&](std::size_t b) {
            std::size_t begin = b * batch, count = std::min(rays.size(), begin + batch) - begin;
            if (engine_.simd_width() == 1) {
                for (std::size_t i = begin; i < begin + count; ++i)
                    out[i] = std::bit_cast<appearance_pixel>(walk_unchecked(start(), rays[i], light, shadows_at).w);
            } else {
                walk_in_rounds(rays.subspan(begin, count), light, shadows_at, std::span(out).subspan(begin, count));
            }
        });
        appearance::check_walked(out);
        return out;
    }

    // The table's record kind (VX_APP_KIND_*).
    std::uint32_t kind() const { return words_.kind; }
    // Rays a lane group walks at once: 1 for the scalar lanes, else 8 or 16.
    unsigned simd_width() const { return engine_.simd_width(); }

    // One ray on the calling thread (safe from many threads at once): what a coarser level's
    // table is re-sampled with (appearance/resample.hpp).
    appearance_pixel walk_one(const ray& r, const appearance_light& light) const {
        state s = start();
        walk_on(s, r, light);
        return std::bit_cast<appearance_pixel>(s.w);
    }

    // A walk under way (appearance/walk_types.h): the walk of one ray through several
    // walkers' pieces, one after another, hands it on (appearance/world/placed_walker.hpp).
    using state = kernels::scalar::vx_app_walk_state;
    static state start() { return kernels::scalar::vx_app_walk_state_start(); }
    // Goes on with `s` along `r` (in this walker's voxels) on the calling thread.
    void walk_on(state& s, const ray& r, const appearance_light& light) const {
        s = walk_unchecked(s, r, light, words_.shadows.at_for(light));
        appearance_pixel p = std::bit_cast<appearance_pixel>(s.w);
        appearance::check_walked({&p, 1});
    }

private:
    // Rays a thread walks in rounds at once: their cursors stay in its cache.
    static constexpr std::size_t batch = 512;

    // What a thread's rounds work in, kept from batch to batch (no allocation a batch).
    struct round_buffers {
        std::vector<kernels::scalar::vx_app_walk_cursor> cursors;
        std::vector<std::uint32_t> tracing, next_tracing;  // the cursors that want a closest hit
        std::vector<std::uint32_t> blending;                // the cursors with a voxel to blend
        std::vector<std::uint32_t> sorted;                  // blending's first entries by faces
        std::vector<ray> rays;
        std::vector<hit> hits;
        cpu_detail::appearance_round round;  // the samples' jobs and samples
        void fit(std::size_t n) {
            cursors.resize(n), rays.resize(n), hits.resize(n), blending.resize(n), sorted.resize(n), round.fit(n);
            tracing.clear(), next_tracing.clear();
        }
    };

    // The walks of `rays` into `out`, in rounds: the closest hits of the rays that want one
    // on the engine's SIMD lanes, then each one's enter; then, while voxels wait to be
    // blended, their samples and a take each (appearance/walk_visit.h). Compact records are
    // sampled on the SIMD lanes in whole lane groups: a voxel that would leave a group part
    // empty waits for the next round's (its ray traces nothing meanwhile), unless no ray is
    // left to trace. Each cursor's steps are the same in any order, so the pixels are too.
    void walk_in_rounds(std::span<const ray> rays, const appearance_light& light, std::uint32_t shadows_at,
                        std::span<appearance_pixel> out) const {
        namespace k = kernels::scalar;
        const k::vx_app_light l = lane_light(light);
        thread_local round_buffers b;
        b.fit(rays.size());
        for (std::size_t i = 0; i < rays.size(); ++i) {
            b.cursors[i] = k::vx_app_walk_begin(cpu_detail::to_lane(rays[i]), start(), light.max_visits);
            if (b.cursors[i].going) b.tracing.push_back(std::uint32_t(i));
        }
        const std::size_t group = words_.kind == VX_APP_KIND_COMPACT ? engine_.simd_width() : 1;
        std::size_t waiting = 0;  // b.blending[0, waiting): the cursors with a voxel to blend
        while (!b.tracing.empty() || waiting > 0) {
            b.next_tracing.clear();
            const std::size_t n = b.tracing.size();
            for (std::size_t j = 0; j < n; ++j) b.rays[j] = cpu_detail::from_lane(b.cursors[b.tracing[j]].r);
            engine_.template trace_here<VX_MODE_CLOSEST>(std::span(b.rays).first(n), std::span(b.hits).first(n));
            for (std::size_t j = 0; j < n; ++j) {
                k::vx_app_walk_cursor& c = b.cursors[b.tracing[j]];
                c = k::vx_app_walk_enter(words_.index.data(), light.max_visits, cpu_detail::to_lane(b.hits[j]), c);
                if (c.row != VX_APP_NO_ROW) b.blending[waiting++] = b.tracing[j];
                else if (c.going) b.next_tracing.push_back(b.tracing[j]);
            }
            while (waiting > 0) {
                const bool last = b.next_tracing.empty();  // no round follows: blend every voxel waiting
                const std::size_t now = last ? waiting : waiting / group * group;
                if (now == 0) break;
                if (group > 1) by_faces(b.cursors, std::span(b.blending).first(now), b.sorted);
                sample(b.cursors, std::span(b.blending).first(now), l, shadows_at, b.round);
                std::size_t kept = 0;
                for (std::size_t j = 0; j < now; ++j) {
                    k::vx_app_walk_cursor& c = b.cursors[b.blending[j]];
                    c = k::vx_app_walk_take(words_.index.data(), words_.kind, light.cutoff, light.max_visits,
                                            b.round.sample(j), c);
                    if (c.row != VX_APP_NO_ROW) b.blending[kept++] = b.blending[j];
                    else if (c.going) b.next_tracing.push_back(b.blending[j]);
                }
                std::copy(b.blending.begin() + std::ptrdiff_t(now), b.blending.begin() + std::ptrdiff_t(waiting),
                          b.blending.begin() + std::ptrdiff_t(kept));
                waiting = kept + (waiting - now);
            }
            std::swap(b.tracing, b.next_tracing);
        }
        for (std::size_t i = 0; i < rays.size(); ++i) out[i] = std::bit_cast<appearance_pixel>(b.cursors[i].s.w);
    }

    // Reorders `which` (cursors whose voxels have compact records) by their records' faces, so
    // that a lane group's records have about as many: the faces' loop runs to the most any
    // lane has (on the bunny a record held 2.1 faces on average, but the loop ran 3.8 times
    // a record). Stable; the takes' order does not matter. `sorted`: room for as many.
    void by_faces(std::span<const kernels::scalar::vx_app_walk_cursor> cursors, std::span<std::uint32_t> which,
                  std::span<std::uint32_t> sorted) const {
        std::array<std::uint32_t, VX_APP_MAX_FACES + 2> start{};  // start[f + 1]: records with f faces
        auto faces_of = [&](std::uint32_t cursor) {
            return std::min<std::uint32_t>(VX_APP_FACES(words_.records[cursors[cursor].row * VX_APP_COMPACT_WORDS + 1]),
                                           VX_APP_MAX_FACES);
        };
        for (std::uint32_t cursor : which) ++start[faces_of(cursor) + 1];
        for (std::size_t f = 1; f < start.size(); ++f) start[f] += start[f - 1];
        for (std::uint32_t cursor : which) sorted[start[faces_of(cursor)]++] = cursor;
        std::copy(sorted.begin(), sorted.begin() + std::ptrdiff_t(which.size()), which.begin());
    }

    // What the voxel each cursor of `which` is to blend shows, into round's samples [0...).
    void sample(std::span<const kernels::scalar::vx_app_walk_cursor> cursors, std::span<const std::uint32_t> which,
                const kernels::scalar::vx_app_light& l, std::uint32_t shadows_at,
                cpu_detail::appearance_round& round) const {
        namespace k = kernels::scalar;
        if (words_.kind != VX_APP_KIND_COMPACT) {
            for (std::size_t j = 0; j < which.size(); ++j)
                round.set_sample(j, k::vx_app_walk_sample(words_.records.data(), words_.faces.data(), words_.kind, l,
                                                          shadows_at, cursors[which[j]]));
            return;
        }
        for (std::size_t j = 0; j < which.size(); ++j) {
            const k::vx_app_walk_cursor& c = cursors[which[j]];
            round.set_job(j, c.row, c.r.dx, c.r.dy, c.r.dz,
                          k::vx_app_walk_light(words_.records.data(), l, shadows_at, c.row));
        }
        cpu_detail::sample_lanes<VX_APP_KIND_COMPACT>(engine_.simd_width(), words_.records.data(),
                                                      words_.faces.data(), round, which.size());
    }

    static cpu_options borrowing(cpu_options o) {
        o.borrow_blob = true;
        return o;
    }

    static kernels::scalar::vx_app_light lane_light(const appearance_light& light) {
        return {light.to_light.x, light.to_light.y, light.to_light.z, light.ambient};
    }

    state walk_unchecked(const state& s, const ray& r, const appearance_light& light, std::uint32_t shadows_at) const {
        static_assert(sizeof(kernels::scalar::vx_app_walk_result) == sizeof(appearance_pixel));
        const kernels::scalar::vx_app_light l = lane_light(light);
        const kernels::scalar::vx_ray lane = cpu_detail::to_lane(r);
        return kernels::scalar::vx_app_walk<Kernel>(blob_.data(), words_.index.data(), words_.records.data(),
                                                    words_.faces.data(), words_.kind, lane, l, light.cutoff,
                                                    light.max_visits, shadows_at, s);
    }

    std::vector<std::uint32_t> blob_;
    appearance::walk_words words_;
    typename Backend::template engine<Kernel> engine_;
};

}  // namespace voxray
