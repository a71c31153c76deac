// An open world's chunks as mesh sources (meshing/world_chunk_source.hpp) and meshes placed
// with cells larger than a voxel (chunk_placement): a LOD-0 world chunk hands out exactly
// the model's voxels in its box, a finer chunk's cells are cut out of a coarser stand-in,
// and a mesh of cells of 2 voxels draws what the ray tracer sees of the model scaled 2x.
#include <cstdint>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>

#include "meshing_models.hpp"
#include "temp_dir.hpp"
#include "voxray/check/raster_hits.hpp"
#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/meshing/chunk_source.hpp"
#include "voxray/meshing/mesher.hpp"
#include "voxray/meshing/world_chunk_source.hpp"
#include "voxray/rays/camera.hpp"
#include "voxray/vulkan/chunk_raster.hpp"
#include "voxray/world/build/model_source.hpp"
#include "voxray/world/build/world_build.hpp"
#include "voxray/world/stream/streamed_world.hpp"

using namespace voxray;

namespace {

std::vector<std::uint8_t> box_bytes(const auto& source, const box3i& box) {
    std::vector<std::uint8_t> out(box.volume());
    read_box(source, box, out.data());
    return out;
}

// The model built into `dir` in 64^3 chunks, and streaming that shows all of it at LOD 0.
residency_options build_with_lod_0_everywhere(const voxel_model& model, const std::filesystem::path& dir) {
    world_build_options build;
    build.chunk_bits = 6;
    build.threads = 2;
    build_world(model_source(model), dir, build);
    residency_options every_chunk_at_lod_0;
    every_chunk_at_lod_0.streaming_factor = 1e9;
    every_chunk_at_lod_0.budget_bytes = std::uint64_t(1) << 40;
    return every_chunk_at_lod_0;
}

}  // namespace

TEST(world_chunk_source, lod_0_chunks_hand_out_the_models_voxels) {
    voxel_model model = test::blob_model(11, box3i{{-70, -10, -40}, {60, 50, 90}});
    test::temp_dir dir;
    streamed_world world(dir.path, build_with_lod_0_everywhere(model, dir.path));
    world.update(glm::dvec3(0.0), true);
    const world_grid& grid = world.manifest().grid;
    std::size_t chunks = 0;
    for (const placement& p : world.residency().placements()) {
        ASSERT_EQ(p.key.lod, 0);
        meshing::world_chunk_source source(*p.chunk, [](std::uint32_t v) { return std::uint8_t(v); });
        glm::ivec3 lo = grid.origin + p.key.cell * grid.edge();
        box3i cells{glm::ivec3(-1), glm::ivec3(grid.edge() + 1)};  // one cell beyond each side reads empty
        auto got = box_bytes(source, cells);
        auto want = box_bytes(model, box3i{lo, lo + grid.edge()});
        std::vector<std::uint8_t> inside;
        glm::ivec3 e = cells.extent();
        for (int z = 1; z < e.z - 1; ++z)
            for (int y = 1; y < e.y - 1; ++y)
                for (int x = 1; x < e.x - 1; ++x) inside.push_back(got[(std::size_t(z) * e.y + y) * e.x + x]);
        EXPECT_EQ(inside, want) << "chunk (" << p.key.cell.x << ", " << p.key.cell.y << ", " << p.key.cell.z << ")";
        std::size_t solid_outside = 0;
        for (std::size_t i = 0; i < got.size(); ++i) solid_outside += got[i] != 0;
        std::size_t solid_inside = 0;
        for (auto v : inside) solid_inside += v != 0;
        EXPECT_EQ(solid_outside, solid_inside) << "cells beyond the chunk read as empty";
        EXPECT_EQ(source.mesh_origins().size(), std::size_t(solid_inside ? 1 : 0));
        ++chunks;
    }
    EXPECT_GT(chunks, 4u);
}

TEST(world_chunk_source, clear_cuts_out_the_cells_of_a_finer_chunk) {
    voxel_model model = test::blob_model(4, box3i{{0, 0, 0}, {64, 64, 64}}, 30);
    test::temp_dir dir;
    streamed_world world(dir.path, build_with_lod_0_everywhere(model, dir.path));
    world.update(glm::dvec3(0.0), true);
    auto shown = world.residency().placements();
    ASSERT_FALSE(shown.empty());
    meshing::world_chunk_source source(*shown[0].chunk, [](std::uint32_t v) { return std::uint8_t(v); });
    source.clear(box3i{{0, 0, 0}, {64, 64, 32}});
    auto cells = box_bytes(source, box3i{{0, 0, 0}, {64, 64, 64}});
    std::size_t solid_low = 0, solid_high = 0;
    for (std::size_t i = 0; i < cells.size(); ++i) (i < cells.size() / 2 ? solid_low : solid_high) += cells[i] != 0;
    EXPECT_EQ(solid_low, 0u);
    EXPECT_GT(solid_high, 0u);
}

TEST(chunk_placement, cells_of_two_voxels_draw_the_model_scaled_twice) {
    // A model meshed in its own cells and placed with cells of 2 voxels at an odd origin,
    // against the ray tracer on the model scaled up 2x voxel by voxel.
    voxel_model cells = test::blob_model(6, box3i{{-20, -10, -30}, {50, 40, 40}});
    glm::ivec3 at{-33, 7, 101};
    voxel_model scaled;
    cells.for_each_voxel([&](glm::ivec3 p, std::uint8_t v) {
        for (int k = 0; k < 8; ++k) scaled.set(at + 2 * p + glm::ivec3(k & 1, (k >> 1) & 1, k >> 2), v);
    });
    std::vector<meshing::chunk_mesh> meshes = test::mesh_all(cells, false);
    std::vector<chunk_placement> placements(meshes.size(), chunk_placement{at, 1});
    chunk_rasterizer raster;
    raster.upload(meshes, std::vector<std::uint32_t>(256, 0xFFFFFFFFu), placements);
    dense_grid grid(scaled);
    tracer<cpu, dense_grid> rays(grid);
    for (int view = 0; view < 3; ++view) {
        raster_view v{.cam = auto_camera(scaled.bounds(), scaled.up_axis, view), .width = 160, .height = 120,
                      .lod_bias = 64.0f};
        raster_frame f = raster.draw(v);
        auto primary = primary_rays(v.cam, v.width, v.height);
        std::vector<hit> hits(primary.size());
        rays.closest_hit(primary, hits);
        auto a = check::compare_raster_hits(f.pixels, hits, v.width, v.height);
        SCOPED_TRACE("view " + std::to_string(view));
        EXPECT_GT(a.covered, 2000u);
        EXPECT_EQ(a.beyond(0.995), 0u) << a.equal << " of " << a.covered;
        EXPECT_EQ(a.off_edges, 0u);
    }
    placements.pop_back();
    EXPECT_THROW(raster.upload(meshes, {}, placements), error);
    EXPECT_THROW(raster.upload(meshes, {}, std::vector<chunk_placement>(meshes.size(), chunk_placement{at, 17})),
                 error);
}
