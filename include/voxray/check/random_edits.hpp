// Seeded random region edits (spheres, boxes, capsules; fill, erase, paint) and the same
// edits applied voxel by voxel to a plain voxel_model: the reference an edited structure
// is checked against, by `voxray check --edits` and by the conformance tests. Regions decide membership in exact integers (edit/regions.hpp), so
// the reference and the structure agree voxel for voxel.
#pragma once
#include <algorithm>
#include <cstdint>
#include <variant>
#include <vector>

#include "voxray/check/ray_sets.hpp"
#include "voxray/edit/region_edit.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray {

// `count` edits inside `area`, each region up to a quarter of its smallest side. Regions
// stay inside `area` (radii shrink near its faces, boxes are cut): a structure that grows
// its world for fills outside (brickmap) would otherwise trace a world with another
// origin than the reference's, which agrees only to float precision on grazing rays.
// Growth has its own tests (tests/brickmap/test_brickmap_bounds.cpp, ..._trace.cpp).
inline std::vector<region_edit> random_edits(const box3i& area, int count, std::uint64_t seed) {
    rng g(seed);
    glm::ivec3 size = glm::max(area.extent(), glm::ivec3(1));
    int reach = std::max(2, std::min({size.x, size.y, size.z}) / 4);
    auto point = [&] { return area.min + glm::ivec3(g.below(size.x), g.below(size.y), g.below(size.z)); };
    // The largest radius around p that stays inside `area`.
    auto room = [&](glm::ivec3 p) {
        glm::ivec3 lo = p - area.min, hi = area.max - 1 - p;
        return std::max(0, std::min({lo.x, lo.y, lo.z, hi.x, hi.y, hi.z}));
    };
    std::vector<region_edit> edits;
    for (int i = 0; i < count; ++i) {
        region_edit e;
        e.op = static_cast<edit_op>(g.below(3));
        e.value = std::uint32_t(1 + g.below(255));
        glm::ivec3 a = point();
        switch (g.below(3)) {
        case 0: e.region = regions::sphere{a, std::min(1 + g.below(reach), room(a))}; break;
        case 1: {
            glm::ivec3 extent(1 + g.below(reach), 1 + g.below(reach), 1 + g.below(reach));
            e.region = regions::box{{a, glm::min(a + extent, area.max)}};
            break;
        }
        default: {
            glm::ivec3 b = point();
            e.region = regions::capsule{a, b, std::min({g.below(3), room(a), room(b)})};
            break;
        }
        }
        edits.push_back(e);
    }
    return edits;
}

// Edit e on every voxel of its region, inside `world` or not: editable structures grow
// their world to hold a fill (brickmap's default), and later erases and paints reach the
// grown part too. `world` is where the caller's structure started; nothing is clipped.
// Returns the voxels written.
inline std::uint64_t apply_to_model(voxel_model& model, const region_edit& e, [[maybe_unused]] const box3i& world) {
    std::uint64_t writes = 0;
    std::visit(
        [&](const auto& region) {
            box3i b = region.bounds();
            for (int z = b.min.z; z < b.max.z; ++z)
                for (int y = b.min.y; y < b.max.y; ++y)
                    for (int x = b.min.x; x < b.max.x; ++x) {
                        glm::ivec3 p(x, y, z);
                        if (!region.contains(p)) continue;
                        ++writes;
                        if (e.op == edit_op::fill) model.set(p, std::uint8_t(e.value));
                        else if (e.op == edit_op::erase) model.set(p, 0);
                        else if (model.get(p)) model.set(p, std::uint8_t(e.value));
                    }
        },
        e.region);
    return writes;
}

}  // namespace voxray
