// world-fly --raster: the open world's shown chunks, each meshed at its LOD (its cells
// decoded, meshing/world_chunk_source.hpp) and drawn by the Vulkan raster path with POP
// levels of detail inside each chunk, beside the ray-traced frame of the same camera.
// Meshes are kept per chunk while it stays shown. Needs the Vulkan backend.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

#include "voxray/model/palette.hpp"
#include "voxray/rays/camera.hpp"
#include "voxray/world/stream/streamed_world.hpp"

namespace voxray::tool {

struct world_raster_frame {
    std::vector<std::uint8_t> rgb;     // sky behind, rows top to bottom
    std::uint64_t quads = 0;           // quads drawn
    std::uint64_t chunks_meshed = 0;   // world chunks meshed this frame (newly shown)
    std::uint64_t chunks_shown = 0;
    // Meshing newly shown chunks, and uploading them when the shown set changed; the draw on the device.
    double mesh_ms = 0, draw_ms = 0;
};

class world_raster {
public:
    // `colours`: the world's attributes are RGBA8 colours, drawn with the nearest entry of
    // `pal`; else they are `pal`'s indices.
    world_raster(const palette& pal, bool colours, int up_axis, float lod_bias);
    ~world_raster();
    world_raster_frame draw(const streamed_world& world, const camera& cam, int width, int height);

private:
    struct state;
    std::unique_ptr<state> state_;
};

}  // namespace voxray::tool
