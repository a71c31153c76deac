// The raster path of chunk meshes in the tool (voxray/vulkan/chunk_raster.hpp): `voxray
// mesh --png` draws a scene's meshes at a level-of-detail bias, and `voxray check --mesh`
// compares level 0 with the ray tracer's primary hits. Both need the Vulkan backend.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "voxray/meshing/chunk_mesh.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::tool {

struct raster_options {
    std::string png;
    int width = 1280, height = 720;
    int view = 0;            // auto_camera's view number
    float lod_bias = 64.0f;  // meshing/pop.h: t = log2(distance) - bias; 64: level 0 everywhere
};

// Draws the meshes from auto_camera(view), sky behind, to a PNG; prints draws and times.
void write_raster_png(const voxel_model& model, const std::vector<meshing::chunk_mesh>& meshes,
                      const raster_options& o);

// Level 0 from `views` views against the dense grid's primary hits: the differing pixels
// off the picture's edges plus those beyond 0.5 % of the covered ones (printed).
std::uint64_t check_raster(const voxel_model& model, const std::vector<meshing::chunk_mesh>& meshes, int views);

}  // namespace voxray::tool
