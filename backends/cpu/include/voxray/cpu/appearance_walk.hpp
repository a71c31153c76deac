// The compositing walk (appearance/walk.inc) on the CPU's scalar lanes, for any structure
// kernel: many rays on a thread pool, each blended front to back through its voxels'
// appearance records. The same source the GPUs run.
//
//   voxray::appearance_walker<voxray::kernels::dense_grid_kernel> walker(blob, table);
//   std::vector<voxray::appearance_pixel> out = walker.walk(rays, light);
#pragma once
#include <bit>
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#if !defined(VOXRAY_LINKED_CPU)
#error "voxray/cpu/appearance_walk.hpp needs voxray::cpu (the scalar lanes the walk runs on): link it"
#endif
#include "voxray/appearance/walk_inputs.hpp"
#include "voxray/core/error.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/cpu/appearance_kernels.hpp"
#include "voxray/cpu/thread_pool.hpp"

namespace voxray::kernels::scalar {
#define VX_APP_WALK_NAME vx_app_walk
#define VX_APP_WALK_PREFIX template <class Kernel>
#define VX_APP_WALK_TRACE(b, r) kernel_lanes<Kernel>::template trace<VX_MODE_CLOSEST>(b, r)
#include "voxray/appearance/walk.inc"
}  // namespace voxray::kernels::scalar

namespace voxray {

template <class Kernel>
class appearance_walker {
public:
    static constexpr const char* backend = "cpu";

    // `blob` is the structure's words, `table` the appearance of its voxels (its rows in the
    // ordinal index's order); both are copied.
    appearance_walker(std::vector<std::uint32_t> blob, const appearance::appearance_table& table,
                      unsigned threads = 0)
        : blob_(std::move(blob)), words_(table), pool_(std::make_unique<cpu_detail::thread_pool>(threads)) {}

    // Rays' directions must be unit vectors (records are evaluated for them).
    std::vector<appearance_pixel> walk(std::span<const ray> rays, const appearance_light& light) const {
        std::vector<appearance_pixel> out(rays.size());
        const std::uint32_t shadows_at = words_.shadows.at_for(light);
        constexpr std::size_t batch = 256;
        pool_->parallel_for((rays.size() + batch - 1) / batch, [&](std::size_t b) {
            for (std::size_t i = b * batch; i < std::min(rays.size(), (b + 1) * batch); ++i)
                out[i] = walk_unchecked(rays[i], light, shadows_at);
        });
        appearance::check_walked(out);
        return out;
    }

    // The table's record kind (VX_APP_KIND_*).
    std::uint32_t kind() const { return words_.kind; }

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
    appearance_pixel walk_unchecked(const ray& r, const appearance_light& light, std::uint32_t shadows_at) const {
        return std::bit_cast<appearance_pixel>(walk_unchecked(start(), r, light, shadows_at).w);
    }
    state walk_unchecked(const state& s, const ray& r, const appearance_light& light, std::uint32_t shadows_at) const {
        static_assert(sizeof(kernels::scalar::vx_app_walk_result) == sizeof(appearance_pixel));
        kernels::scalar::vx_app_light l{light.to_light.x, light.to_light.y, light.to_light.z, light.ambient};
        kernels::scalar::vx_ray lane{r.origin.x,    r.origin.y,    r.origin.z,    r.tmin,
                                     r.direction.x, r.direction.y, r.direction.z, r.tmax};
        return kernels::scalar::vx_app_walk<Kernel>(blob_.data(), words_.index.data(), words_.records.data(),
                                                    words_.faces.data(), words_.kind, lane, l, light.cutoff,
                                                    light.max_visits, shadows_at, s);
    }

    std::vector<std::uint32_t> blob_;
    appearance::walk_words words_;
    std::unique_ptr<cpu_detail::thread_pool> pool_;
};

}  // namespace voxray
