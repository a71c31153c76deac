// A region cut from any structure as a voxel model, to become an entity model (a piece
// of the world that breaks off and moves). The source is anything with read_box
// (meshing/chunk_source.hpp: a voxel model, and each structure's <structure>/read_box.hpp),
// so what is cut is what is traced, edits included. The voxels keep their own coordinates:
// an instance with no rotation at the centre of the model's bounds stands where they were.
#pragma once
#include <cstdint>
#include <vector>

#include "voxray/core/box.hpp"
#include "voxray/core/error.hpp"
#include "voxray/entities/layout.h"
#include "voxray/meshing/chunk_source.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray {

template <class Source>
voxel_model region_model(const Source& source, const box3i& box) {
    std::int64_t e[3];  // in 64 bits: the edges of any two int corners
    for (int a = 0; a < 3; ++a) e[a] = std::int64_t(box.max[a]) - std::int64_t(box.min[a]);
    for (int a = 0; a < 3; ++a)
        if (e[a] < 1 || e[a] > VX_EM_MAX_EDGE)
            fail("region model: the region is ", e[0], " x ", e[1], " x ", e[2], " voxels; each edge must lie in 1..",
                 VX_EM_MAX_EDGE, " (an entity model's limit)");
    std::vector<std::uint8_t> materials(box.volume());
    read_box(source, box, materials.data());
    voxel_model out;
    std::size_t i = 0;
    for (int z = box.min.z; z < box.max.z; ++z)
        for (int y = box.min.y; y < box.max.y; ++y)
            for (int x = box.min.x; x < box.max.x; ++x, ++i)
                if (materials[i] != 0) out.set({x, y, z}, materials[i]);
    if constexpr (requires { source.palette(); }) out.palette() = source.palette();
    return out;
}

}  // namespace voxray
