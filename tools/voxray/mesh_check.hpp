// voxray check --mesh: the chunk meshes of a scene against their references (see
// mesh_check.cpp); returns the mismatch count.
#pragma once
#include <cstddef>
#include <cstdint>

#include "voxray/model/voxel_model.hpp"

namespace voxray::tool {

struct mesh_check_options {
    int views = 10000;
    int raster_views = 4;  // views of the raster comparison
    std::size_t kernel_chunks = 64;  // chunks the mesher kernel is compared on (evenly spread)
    std::uint64_t seed = 1;
    unsigned threads = 2;
};

std::uint64_t check_mesh(const voxel_model& model, const mesh_check_options& o);

}  // namespace voxray::tool
