// The raster path of chunk meshes in the tool (voxray/vulkan/chunk_raster.hpp): `voxray
// mesh --png` draws a scene's meshes at a level-of-detail bias, and `voxray check --mesh`
// compares level 0 with the ray tracer's primary hits. Both need the Vulkan backend.
#pragma once
#include <cstdint>
#include <memory>
#include <span>
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

// Image error of coarser meshes against the level-0 picture of the same chunks, one view
// (auto_camera's first, 512 x 288), all in one grey so that only the geometry differs:
// RMS difference of the 8-bit colours over the pixels either picture covers (an empty
// pixel counts as black). For the POP levels and for meshes of other tools (meshoptimizer's
// simplifications in mesh-bench). Without the Vulkan backend available() is false.
class level_images {
public:
    level_images(const std::vector<meshing::chunk_mesh>& meshes, int up_axis);
    ~level_images();
    bool available() const;
    double pop_rmse(int level);
    double triangles_rmse(std::span<const float> positions, std::span<const std::uint32_t> indices);

private:
    struct state;
    std::unique_ptr<state> state_;
};

}  // namespace voxray::tool
