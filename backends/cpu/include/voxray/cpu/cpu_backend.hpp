// The CPU backends: voxray::cpu runs the portable kernel on SIMD lanes (one ray per lane,
// kernels::simd_width lanes refilled as rays finish), voxray::cpu_scalar runs the very same kernel one
// ray at a time. Both use every core.
#pragma once
#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/cpu/thread_pool.hpp"
#include "voxray/kernels/cpu_lanes.hpp"
#include "voxray/core/word_range.hpp"
#include "voxray/sync/dirty_ranges.hpp"

namespace voxray {

struct cpu_options {
    unsigned threads = 0;  // 0: one per hardware thread
};

namespace cpu_detail {

// Rays a worker takes at a time: large enough to amortize the hand-out, small enough
// to balance the load across threads.
inline constexpr std::size_t batch_rays = 1024;

inline kernels::scalar::vx_ray to_lane(const ray& r) {
    return {r.origin.x, r.origin.y, r.origin.z, r.tmin, r.direction.x, r.direction.y, r.direction.z, r.tmax};
}

inline hit from_lane(const kernels::scalar::vx_hit& h) {
    hit out;
    out.t = h.t;
    out.voxel = {h.x, h.y, h.z};
    out.normal = static_cast<face>(h.face);
    out.material = h.material;
    out.steps = h.steps;
    out.status = h.status;
    return out;
}

// The SIMD stream: `streams` groups of simd_width lanes, each lane tracing one ray through
// the kernel's state machine. Whenever lanes finish, their hits are written out and the
// lanes restart with the next rays, so no lane idles while another ray is still long (as
// it would with fixed packets). Two independent groups are stepped in turn so that one
// group's gathers overlap the other's arithmetic (a single group is latency-bound). Per
// ray, the arithmetic is exactly the scalar kernel's: results are identical bit for bit.
template <class Kernel, std::uint32_t Mode>
void trace_stream(const std::uint32_t* blob, const ray* rays, hit* hits, std::size_t count) {
    using namespace kernels::simd;
    using K = kernel_lanes<Kernel>;
    constexpr int W = kernels::simd_width;
    constexpr int streams = 2;
    const typename K::header g = K::load(blob);
    // An invalid ray (tmin > tmax) is a miss before its first step: it fills idle lanes.
    const ray idle{glm::vec3(0.0f), 1.0f, glm::vec3(1.0f), 0.0f};
    auto load = [](vx_ray& r, int k, const ray& in) {
        r.ox[k] = in.origin.x; r.oy[k] = in.origin.y; r.oz[k] = in.origin.z; r.tmin[k] = in.tmin;
        r.dx[k] = in.direction.x; r.dy[k] = in.direction.y; r.dz[k] = in.direction.z; r.tmax[k] = in.tmax;
    };
    struct group {
        typename K::state state;
        vx_ray rays;
        std::size_t lane_ray[W];
        bool busy = true;
    } groups[streams];
    std::size_t next = 0;
    for (auto& q : groups) {
        for (int k = 0; k < W; ++k) {
            q.lane_ray[k] = next < count ? next++ : count;
            load(q.rays, k, q.lane_ray[k] < count ? rays[q.lane_ray[k]] : idle);
        }
        q.state = K::begin(g, q.rays);
    }
    // Writes out finished lanes and restarts them; false once the group has nothing left.
    // Refilling costs a finish, a begin and a lane merge of the whole state, so it waits
    // until half of the lanes are done (or the rays run out and the group drains).
    auto refill = [&](group& q) {
        vx_mask finished = K::status(q.state) != VX_STATUS_ACTIVE;
        int done = 0;
        for (int k = 0; k < W; ++k) done += finished[k] != 0;
        if (done == 0 || (done < W / 2 && next < count)) return true;
        vx_hit h = K::template finish<Mode>(blob, g, q.state);
        vx_mask restart = vx_i32_splat(0);
        bool busy = false;
        for (int k = 0; k < W; ++k) {
            if (finished[k] && q.lane_ray[k] < count) {
                hits[q.lane_ray[k]] = from_lane({h.t[k], h.x[k], h.y[k], h.z[k], h.face[k], h.material[k], h.steps[k], h.status[k]});
                q.lane_ray[k] = next < count ? next++ : count;
                if (q.lane_ray[k] < count) {
                    load(q.rays, k, rays[q.lane_ray[k]]);
                    restart[k] = -1;
                }
            }
            busy |= q.lane_ray[k] < count;
        }
        if (vx_any(restart)) q.state = vx_select_state(restart, K::begin(g, q.rays), q.state);
        return busy;
    };
    for (bool any_busy = true; any_busy;) {
        any_busy = false;
        for (auto& q : groups) {
            if (!q.busy) continue;
            q.busy = refill(q);
            if (q.busy) q.state = K::step(blob, g, q.state);
            any_busy |= q.busy;
        }
    }
}

template <bool Simd, class Kernel>
class cpu_engine {
public:
    explicit cpu_engine(cpu_options options) : pool_(std::make_unique<thread_pool>(options.threads)) {}

    void upload(std::span<const std::uint32_t> blob) {
        blob_.assign(blob.begin(), blob.end());
        count_upload(blob.size_bytes());
    }

    // Copies only the words of `ranges` (any order; overlaps and empty ranges allowed)
    // into the engine's copy of the blob; a blob of another size is copied whole.
    void update_ranges(std::span<const std::uint32_t> blob, std::span<const word_range> ranges) {
        if (blob.size() != blob_.size()) return upload(blob);
        std::uint64_t words = 0;
        for (const word_range& r : sync::normalize_ranges(ranges, blob.size())) {
            std::copy_n(blob.data() + r.offset, r.count, blob_.data() + r.offset);
            words += r.count;
        }
        count_upload(words * sizeof(std::uint32_t));
    }

    // Bytes the last upload or update copied, and their running total.
    std::uint64_t bytes_uploaded_last_update() const { return last_bytes_; }
    std::uint64_t bytes_uploaded_total() const { return total_bytes_; }

    // For tests and diagnostics, like the GPU engines': a copy of the blob traced.
    std::vector<std::uint32_t> download_blob() const { return blob_; }

    void trace(std::span<const ray> rays, std::span<hit> hits, std::uint32_t mode) {
        // The mode becomes a constant of the kernel: any-hit compiles to its own code.
        if (mode == VX_MODE_ANY) trace_mode<VX_MODE_ANY>(rays, hits);
        else trace_mode<VX_MODE_CLOSEST>(rays, hits);
    }

    unsigned threads() const { return pool_->size(); }

private:
    template <std::uint32_t Mode>
    void trace_mode(std::span<const ray> rays, std::span<hit> hits) {
        const std::uint32_t* blob = blob_.data();
        std::size_t batches = (rays.size() + batch_rays - 1) / batch_rays;
        pool_->parallel_for(batches, [&](std::size_t b) {
            std::size_t begin = b * batch_rays, end = std::min(rays.size(), begin + batch_rays);
            if constexpr (Simd) {
                trace_stream<Kernel, Mode>(blob, &rays[begin], &hits[begin], end - begin);
            } else {
                using K = kernels::scalar::kernel_lanes<Kernel>;
                for (std::size_t i = begin; i < end; ++i) hits[i] = from_lane(K::template trace<Mode>(blob, to_lane(rays[i])));
            }
        });
    }

    void count_upload(std::uint64_t bytes) {
        last_bytes_ = bytes;
        total_bytes_ += bytes;
    }

    std::unique_ptr<thread_pool> pool_;
    std::vector<std::uint32_t> blob_;
    std::uint64_t last_bytes_ = 0, total_bytes_ = 0;
};

}  // namespace cpu_detail

template <bool Simd>
struct cpu_backend {
    using options = cpu_options;
    template <class Kernel>
    using engine = cpu_detail::cpu_engine<Simd, Kernel>;
    static constexpr const char* name = Simd ? "cpu" : "cpu-scalar";
};

using cpu = cpu_backend<true>;
using cpu_scalar = cpu_backend<false>;

}  // namespace voxray
