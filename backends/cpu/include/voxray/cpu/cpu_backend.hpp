// The CPU backends: voxray::cpu runs the portable kernel on SIMD lanes (one ray per lane,
// 16 lanes with AVX-512 where the CPU has it, else 8, refilled as rays finish),
// voxray::cpu_scalar runs the very same kernel one ray at a time. Both use every core.
#pragma once
#include <algorithm>
#include <bit>
#include <cstring>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/cpu/thread_pool.hpp"
#include "voxray/cpu/lanes.hpp"
#include "voxray/core/word_range.hpp"
#include "voxray/sync/dirty_ranges.hpp"
#include "voxray/sync/upload_plan.hpp"

namespace voxray {

// Worker threads that several CPU tracers may share (cpu_options::pool): calls from any
// number of tracers and threads overlap safely (see thread_pool.hpp).
using cpu_thread_pool = cpu_detail::thread_pool;

struct cpu_options {
    unsigned threads = 0;     // 0: one per hardware thread (ignored when `pool` is given)
    // voxray::cpu lanes: 0 = the widest the CPU runs (16 with AVX-512, 8 with AVX2, else 1:
    // the scalar kernel), or 8 or 16 to insist (an error where the CPU lacks the ISA).
    unsigned simd_width = 0;
    // Share these workers instead of starting a pool of its own:
    //   auto pool = std::make_shared<voxray::cpu_thread_pool>(8);
    //   voxray::tracer<voxray::cpu, voxray::brickmap<>> a(map, {.pool = pool}), b(grid, {.pool = pool});
    std::shared_ptr<cpu_thread_pool> pool = nullptr;  // (an initializer: no -Wmissing-field-initializers in {.threads = 1})
    // Trace the structure's own blob in place instead of a copy (no upload cost, no second
    // copy in memory). The caller promises that the structure is neither edited, moved nor
    // destroyed while this tracer traces; update() after an edit then only re-points (the
    // structure may have reallocated its words). Off: the tracer holds a snapshot, and the
    // structure may change freely between updates.
    bool borrow_blob = false;
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

inline kernels::scalar::vx_hit to_lane(const hit& h) {
    return {h.t, h.voxel.x, h.voxel.y, h.voxel.z, std::uint32_t(h.normal), h.material, h.steps, h.status};
}

inline ray from_lane(const kernels::scalar::vx_ray& r) {
    ray out;
    out.origin = {r.ox, r.oy, r.oz}, out.direction = {r.dx, r.dy, r.dz};
    out.tmin = r.tmin, out.tmax = r.tmax;
    return out;
}

}  // namespace cpu_detail

#if !VOXRAY_CPU_SIMD_LANES
namespace kernels {
// Whether voxray::kernels holds the streams of structure kernel Kernel (true for the
// registered ones: voxray/generated/cpu_kernel_instances.hpp).
template <class Kernel>
inline constexpr bool linked_streams = false;
}  // namespace kernels
#endif
}  // namespace voxray

// The stream, once per SIMD lane set (see simd_stream.inc): defined where the lane sets are
// compiled, else only declared, voxray::kernels holding its instances (cpu/lanes.hpp).
#define VOXRAY_LANE_SET_BODY "voxray/cpu/simd_stream.inc"
#include "voxray/cpu/each_lane_set.inc"

namespace voxray {

namespace kernels::scalar {
// The scalar kernel over a batch, one ray after another (the cpu-scalar backend, and
// voxray::cpu on a CPU without AVX2).
template <class Kernel, std::uint32_t Mode>
void trace_stream(const std::uint32_t* blob, const voxray::ray* rays, voxray::hit* hits, std::size_t count) {
    using K = kernel_lanes<Kernel>;
    for (std::size_t i = 0; i < count; ++i)
        hits[i] = cpu_detail::from_lane(K::template trace<Mode>(blob, cpu_detail::to_lane(rays[i])));
}
}  // namespace kernels::scalar

// The streams of one structure kernel in one lane set (scalar, simd8, simd16), both
// trace modes: what the compiled voxray::kernels library instantiates once, one source
// file per kernel and lane set, and what its users then declare `extern` instead of
// compiling again (PREFIX: `extern` or nothing; voxray/generated/cpu_kernel_instances.hpp).
#define VOXRAY_CPU_STREAM_INSTANCES(PREFIX, LANES, KERNEL)                                                   \
    PREFIX template void voxray::kernels::LANES::trace_stream<KERNEL, VX_MODE_CLOSEST>(                      \
        const std::uint32_t*, const voxray::ray*, voxray::hit*, std::size_t);                                \
    PREFIX template void voxray::kernels::LANES::trace_stream<KERNEL, VX_MODE_ANY>(                          \
        const std::uint32_t*, const voxray::ray*, voxray::hit*, std::size_t);

namespace cpu_detail {

template <bool Simd, class Kernel>
class cpu_engine {
public:
    explicit cpu_engine(cpu_options options)
        : pool_(options.pool ? std::move(options.pool) : std::make_shared<thread_pool>(options.threads)),
          width_(choose_width(options.simd_width)),
          borrow_(options.borrow_blob) {}
    // Moves keep view_ valid (a moved vector keeps its buffer); a copy would not.
    cpu_engine(const cpu_engine&) = delete;
    cpu_engine& operator=(const cpu_engine&) = delete;
    cpu_engine(cpu_engine&&) noexcept = default;
    cpu_engine& operator=(cpu_engine&&) noexcept = default;

    void upload(std::span<const std::uint32_t> blob) {
        if (borrow_) {
            view_ = blob;  // the structure's own words: nothing copied
            return ledger_.count(0);
        }
        blob_.assign(blob.begin(), blob.end());
        view_ = blob_;
        ledger_.count(blob.size_bytes());
    }

    // Copies only the words of `ranges` (any order; overlaps and empty ranges allowed)
    // into the engine's copy of the blob; a blob of another size is copied whole.
    void update_ranges(std::span<const std::uint32_t> blob, std::span<const word_range> ranges) {
        if (borrow_ || blob.size() != blob_.size()) return upload(blob);
        std::uint64_t words = 0;
        for (const word_range& r : sync::normalize_ranges(ranges, blob.size())) {
            std::copy_n(blob.data() + r.offset, r.count, blob_.data() + r.offset);
            words += r.count;
        }
        ledger_.count(words * sizeof(std::uint32_t));
    }

    // The blob grew and kept every old word in place (tracer.hpp, grows_in_place): the
    // copy grows (new words zero) and takes only the words of `ranges`.
    void grow_ranges(std::span<const std::uint32_t> blob, std::span<const word_range> ranges) {
        if (borrow_ || blob.size() < blob_.size()) return upload(blob);
        blob_.resize(blob.size(), 0u);
        view_ = blob_;
        update_ranges(blob, ranges);
    }

    // Bytes the last upload or update copied, and their running total.
    std::uint64_t bytes_uploaded_last_update() const { return ledger_.last(); }
    std::uint64_t bytes_uploaded_total() const { return ledger_.total(); }

    // For tests and diagnostics, like the GPU engines': a copy of the blob traced.
    std::vector<std::uint32_t> download_blob() const { return {view_.begin(), view_.end()}; }

    // The words traced, for passes that run beside the trace (world/frame/frame.hpp).
    std::span<const std::uint32_t> blob_view() const { return view_; }

    // The workers this engine runs on (shared with other tracers when cpu_options::pool was given).
    const std::shared_ptr<thread_pool>& pool() const { return pool_; }

    void trace(std::span<const ray> rays, std::span<hit> hits, std::uint32_t mode) {
        // The mode becomes a constant of the kernel: any-hit compiles to its own code.
        if (mode == VX_MODE_ANY) trace_mode<VX_MODE_ANY>(rays, hits);
        else trace_mode<VX_MODE_CLOSEST>(rays, hits);
    }

    // Rays on the calling thread alone, in this engine's lanes (no pool): for callers that
    // share the work out themselves (cpu/appearance_walk.hpp). The same hits as trace().
    template <std::uint32_t Mode>
    void trace_here(std::span<const ray> rays, std::span<hit> hits) const {
        const std::uint32_t* blob = view_.data();
        // cpu-scalar compiles only the scalar stream: the SIMD ones exist in voxray::cpu alone.
        if constexpr (Simd) {
#if !VOXRAY_CPU_SIMD_LANES
            static_assert(kernels::linked_streams<Kernel>,
                          "voxray::kernels holds the SIMD streams of the structures registered with "
                          "voxray_add_structure only: register this one, or leave voxray::kernels unlinked");
#endif
            if (width_ == 16)
                return kernels::simd16::trace_stream<Kernel, Mode>(blob, rays.data(), hits.data(), rays.size());
            if (width_ == 8)
                return kernels::simd8::trace_stream<Kernel, Mode>(blob, rays.data(), hits.data(), rays.size());
        }
        kernels::scalar::trace_stream<Kernel, Mode>(blob, rays.data(), hits.data(), rays.size());
    }

    // One ray with the scalar kernel on the calling thread: no pool, no lane set-up
    // (tracer::closest_hit(const ray&)). Same hit as trace(), bit for bit.
    hit trace_one(const ray& r, std::uint32_t mode) const {
        using K = kernels::scalar::kernel_lanes<Kernel>;
        if (mode == VX_MODE_ANY) return from_lane(K::template trace<VX_MODE_ANY>(view_.data(), to_lane(r)));
        return from_lane(K::template trace<VX_MODE_CLOSEST>(view_.data(), to_lane(r)));
    }

    unsigned threads() const { return pool_->size(); }
    // Rays traced at once per lane group: 1 for cpu-scalar, else 8 or 16.
    unsigned simd_width() const { return width_; }

private:
    static unsigned choose_width(unsigned asked) {
        if (!Simd) return 1;
        if (asked == 0) return kernels::cpu_has_avx512() ? 16u : (kernels::cpu_has_avx2() ? 8u : 1u);
        if (asked != 8 && asked != 16) fail("cpu backend: simd_width must be 0, 8 or 16, not ", asked);
        if (asked == 16 && !kernels::cpu_has_avx512())
            fail("cpu backend: simd_width 16 needs AVX-512 (avx512f/dq/bw/vl), which this CPU does not have");
        if (asked == 8 && !kernels::cpu_has_avx2())
            fail("cpu backend: simd_width 8 needs AVX2, which this CPU does not have");
        return asked;
    }

    template <std::uint32_t Mode>
    void trace_mode(std::span<const ray> rays, std::span<hit> hits) {
        std::size_t batches = (rays.size() + batch_rays - 1) / batch_rays;
        auto batch = [&](std::size_t b) {
            std::size_t begin = b * batch_rays, count = std::min(rays.size(), begin + batch_rays) - begin;
            trace_here<Mode>(rays.subspan(begin, count), hits.subspan(begin, count));
        };
        // A single batch runs on the calling thread: waking the pool would cost more than it saves.
        if (batches == 1) batch(0);
        else pool_->parallel_for(batches, batch);
    }

    std::shared_ptr<thread_pool> pool_;
    unsigned width_ = 1;  // 1: the scalar kernel
    bool borrow_ = false;
    std::vector<std::uint32_t> blob_;     // the copy traced, unless borrowing
    std::span<const std::uint32_t> view_;  // what is traced: blob_, or the structure's words
    sync::upload_ledger ledger_;
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

// Linked with voxray::kernels: the streams of every registered structure are compiled
// there once, so this translation unit only declares them.
#if defined(VOXRAY_CPU_KERNELS_LINKED)
#include "voxray/generated/cpu_kernel_instances.hpp"
#endif
