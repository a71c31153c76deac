// The compositing walk (appearance/walk.inc) on the CPU's scalar lanes, for any structure
// kernel: many rays on a thread pool, each blended front to back through its voxels'
// appearance records. The same source the GPUs run.
//
//   voxray::appearance_walker<voxray::kernels::dense_grid_kernel> walker(blob, table);
//   std::vector<voxray::appearance_pixel> out = walker.walk(rays, light);
#pragma once
#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#if !defined(VOXRAY_LINKED_CPU)
#error "voxray/cpu/appearance_walk.hpp needs voxray::cpu (the scalar lanes the walk runs on): link it"
#endif
#include "voxray/appearance/ordinal_index.hpp"
#include "voxray/appearance/table.hpp"
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

using appearance_pixel = kernels::scalar::vx_app_walk_result;

struct appearance_light {
    glm::vec3 to_light{0.0f, 1.0f, 0.0f};  // unit
    float ambient = 0.2f;
    float cutoff = 1e-3f;         // stop below this transmittance (the paper's)
    std::uint32_t max_visits = 4096;
};

template <class Kernel>
class appearance_walker {
public:
    // `blob` is the structure's words, `table` the appearance of its voxels (its rows in the
    // ordinal index's order); both are copied.
    appearance_walker(std::vector<std::uint32_t> blob, const appearance::appearance_table& table,
                      unsigned threads = 0)
        : blob_(std::move(blob)), index_(appearance::ordinal_index(table)), records_(table.words),
          faces_(table.faces), kind_(kind_of(table.kind)),
          pool_(std::make_unique<cpu_detail::thread_pool>(threads)) {
        if (faces_.empty()) faces_.push_back(0);  // a valid pointer for tables without faces
        if (records_.empty()) records_.push_back(0);
    }

    // Rays' directions must be unit vectors (records are evaluated for them).
    std::vector<appearance_pixel> walk(std::span<const ray> rays, const appearance_light& light) const {
        std::vector<appearance_pixel> out(rays.size());
        kernels::scalar::vx_app_light l{light.to_light.x, light.to_light.y, light.to_light.z, light.ambient};
        constexpr std::size_t batch = 256;
        pool_->parallel_for((rays.size() + batch - 1) / batch, [&](std::size_t b) {
            for (std::size_t i = b * batch; i < std::min(rays.size(), (b + 1) * batch); ++i) {
                const ray& r = rays[i];
                kernels::scalar::vx_ray lane{r.origin.x,    r.origin.y,    r.origin.z,    r.tmin,
                                             r.direction.x, r.direction.y, r.direction.z, r.tmax};
                out[i] = kernels::scalar::vx_app_walk<Kernel>(blob_.data(), index_.data(), records_.data(),
                                                              faces_.data(), kind_, lane, l, light.cutoff,
                                                              light.max_visits);
            }
        });
        for (const appearance_pixel& p : out)
            if (p.status == VX_APP_WALK_NO_RECORD)
                fail("appearance walk: voxel (", p.x, ", ", p.y, ", ", p.z,
                     ") of the structure has no row in the appearance table (a table of other voxels?)");
        return out;
    }

private:
    static std::uint32_t kind_of(appearance::record_kind k) {
        switch (k) {
        case appearance::record_kind::averages: return VX_APP_KIND_AVERAGES;
        case appearance::record_kind::compact: return VX_APP_KIND_COMPACT;
        case appearance::record_kind::six: return VX_APP_KIND_SIX;
        case appearance::record_kind::sggx: return VX_APP_KIND_SGGX;
        }
        fail("appearance walk: unknown record kind ", int(k));
    }

    std::vector<std::uint32_t> blob_, index_, records_, faces_;
    std::uint32_t kind_;
    std::unique_ptr<cpu_detail::thread_pool> pool_;
};

}  // namespace voxray
