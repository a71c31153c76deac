// Editing helpers of the tool: the seeded random edits and their voxel-by-voxel reference
// come from voxray/check/random_edits.hpp; here, what an edit writes (for the rates of
// `voxray bench --edits`).
#pragma once
#include <cstdint>
#include <variant>
#include <vector>

#include "voxray/check/random_edits.hpp"
#include "voxray/edit/region_edit.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::tool {

// Voxels of a region inside `world` (what an edit writes).
template <class Region>
std::uint64_t region_voxels(const Region& region, const box3i& world) {
    box3i b = region.bounds();
    b.min = glm::max(b.min, world.min);
    b.max = glm::min(b.max, world.max);
    std::uint64_t n = 0;
    for (int z = b.min.z; z < b.max.z; ++z)
        for (int y = b.min.y; y < b.max.y; ++y) {
            auto [x0, x1] = region.span(y, z, b.min.x, b.max.x);
            n += std::uint64_t(std::max(0, x1 - x0));
        }
    return n;
}

}  // namespace voxray::tool
