// Precomputed shadows for one directional light (issue 25, item 3; the paper's §4): each
// row's visibility of the light, the transmittance of one shadow ray walked through the
// structure and its appearance table (the compositing walk, appearance/walk.inc), stored as
// a byte a row in the table (table.hpp, `shadows`). The walk then lights a voxel's direct
// term by it: colour * (ambient + visibility * (1 - ambient) * max(0, n . l)).
//
// The ray runs from the voxel's centre towards the light and starts `skip` voxels out (the
// paper's 1.5, after Vicini et al.): a voxel does not shadow itself, nor do the neighbours
// it was voxelized with, which would darken every lit surface. The opacities the walk reads
// are the same both ways along a line, so this is the paper's ray from the light reversed.
// Six directions records are lit when made and ignore shadows.
#pragma once
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <glm/geometric.hpp>

#include "voxray/appearance/pixel.hpp"
#include "voxray/appearance/precompute.hpp"
#include "voxray/appearance/table.hpp"
#include "voxray/core/error.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/model/build_threads.hpp"

namespace voxray::appearance {

struct shadow_options {
    float skip = 1.5f;        // voxels from the centre before anything may shadow
    float cutoff = 1e-3f;     // a shadow ray stops below this transmittance: fully shadowed
    unsigned threads = 0;     // 0: every hardware thread
};

// A visibility as the table stores it: round(255 v), v clamped to [0, 1].
inline std::uint8_t visibility_code(float v) {
    return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
}

// The shadows of `to_light` (unit, towards the light) for every row of `table`, which
// `walker` (a CPU appearance_walker of the table's structure and this table, without
// shadows) walks; stored in table.shadows. The same for any thread count. stats: one ray a
// row.
template <class Walker>
void precompute_shadows(const Walker& walker, appearance_table& table, glm::vec3 to_light,
                        const shadow_options& o = {}, precompute_stats* stats = nullptr) {
    if (!(std::abs(glm::length(to_light) - 1.0f) < 1e-3f))
        fail("appearance shadows: the direction to the light (", to_light.x, ", ", to_light.y, ", ", to_light.z,
             ") is not a unit vector");
    if (!(o.skip >= 0.0f) || !std::isfinite(o.skip))
        fail("appearance shadows: skip ", o.skip, " voxels is not a finite distance >= 0");
    auto start = std::chrono::steady_clock::now();
    std::vector<std::uint8_t> visibility(table.size(), 0);
    unsigned threads = resolve_build_threads(o.threads, table.size());
    // Row r goes to thread r % threads: each ray depends on its row only.
    run_build_threads(threads, [&](unsigned thread) {
        for (std::size_t row = thread; row < table.size(); row += threads) {
            ray r;
            r.origin = glm::vec3(table.voxels[row]) + 0.5f, r.direction = to_light;
            r.tmin = o.skip, r.tmax = std::numeric_limits<float>::infinity();
            appearance_pixel p = walker.walk_one(r, {.to_light = to_light, .ambient = 1.0f, .cutoff = o.cutoff,
                                                     .shadows = false});
            visibility[row] = visibility_code(p.transmittance < o.cutoff ? 0.0f : p.transmittance);
        }
    });
    table.shadows = {to_light, std::move(visibility)};
    if (stats) {
        stats->voxels = stats->rays = table.size();
        stats->hits = 0;
        stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
}

}  // namespace voxray::appearance
