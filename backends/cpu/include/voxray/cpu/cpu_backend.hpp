// The CPU backends: voxray::cpu runs the portable kernel on SIMD lanes (one ray per lane,
// packets of kernels::simd_width rays), voxray::cpu_scalar runs the very same kernel one
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

// Traces up to simd_width rays as one packet. Unused lanes carry an invalid ray
// (tmin > tmax), which the kernel turns into a miss before its first step.
template <class Kernel>
void trace_packet(const std::uint32_t* blob, const ray* rays, hit* hits, std::size_t n, std::uint32_t mode) {
    using namespace kernels::simd;
    vx_ray r;
    for (int k = 0; k < width; ++k) {
        ray in = k < int(n) ? rays[k] : ray{glm::vec3(0), 1.0f, glm::vec3(1), 0.0f};
        r.ox[k] = in.origin.x; r.oy[k] = in.origin.y; r.oz[k] = in.origin.z; r.tmin[k] = in.tmin;
        r.dx[k] = in.direction.x; r.dy[k] = in.direction.y; r.dz[k] = in.direction.z; r.tmax[k] = in.tmax;
    }
    vx_hit h = lanes::trace(Kernel{}, blob, r, mode);
    for (int k = 0; k < int(n); ++k) {
        hits[k] = from_lane({h.t[k], h.x[k], h.y[k], h.z[k], h.face[k], h.material[k], h.steps[k], h.status[k]});
    }
}

template <bool Simd, class Kernel>
class cpu_engine {
public:
    explicit cpu_engine(cpu_options options) : pool_(std::make_unique<thread_pool>(options.threads)) {}

    void upload(std::span<const std::uint32_t> blob) { blob_.assign(blob.begin(), blob.end()); }

    void trace(std::span<const ray> rays, std::span<hit> hits, std::uint32_t mode) {
        const std::uint32_t* blob = blob_.data();
        std::size_t batches = (rays.size() + batch_rays - 1) / batch_rays;
        pool_->parallel_for(batches, [&](std::size_t b) {
            std::size_t begin = b * batch_rays, end = std::min(rays.size(), begin + batch_rays);
            if constexpr (Simd) {
                for (std::size_t i = begin; i < end; i += kernels::simd_width)
                    trace_packet<Kernel>(blob, &rays[i], &hits[i], std::min<std::size_t>(kernels::simd_width, end - i), mode);
            } else {
                for (std::size_t i = begin; i < end; ++i)
                    hits[i] = from_lane(kernels::scalar::lanes::trace(Kernel{}, blob, to_lane(rays[i]), mode));
            }
        });
    }

    unsigned threads() const { return pool_->size(); }

private:
    std::unique_ptr<thread_pool> pool_;
    std::vector<std::uint32_t> blob_;
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
