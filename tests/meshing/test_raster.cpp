// The raster path of chunk meshes (voxray/vulkan/chunk_raster.hpp) on the Vulkan device
// (lavapipe here): at level of detail 0 every pixel's voxel and face (the identity
// attachment) equals the ray tracer's primary hit through that pixel's centre, except
// where a voxel edge passes through the centre itself; culling changes no pixel; fixed
// levels draw their prefixes; triangles of the same quads draw the same picture; bad
// input is refused with the numbers.
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "meshing_models.hpp"
#include "test_data.hpp"
#include "voxray/check/raster_hits.hpp"
#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/io/vox_reader.hpp"
#include "voxray/meshing/chunk_source.hpp"
#include "voxray/meshing/mesher.hpp"
#include "voxray/meshing/quad_corners.hpp"
#include "voxray/meshing/squashed.hpp"
#include "voxray/rays/camera.hpp"
#include "voxray/rays/shading.hpp"
#include "voxray/scenes/chunk_scenes.hpp"
#include "voxray/vulkan/chunk_raster.hpp"
#include "voxray/vulkan/triangle_raster.hpp"

using namespace voxray;

namespace {

std::vector<std::uint32_t> colours_of(const palette& p) {
    std::vector<std::uint32_t> colours(palette::size);
    for (int i = 0; i < palette::size; ++i) colours[std::size_t(i)] = pack_rgba(p[std::uint8_t(i)].colour);
    return colours;
}

void expect_raster_matches_rays(const voxel_model& model, const std::string& name, int views) {
    auto meshes = test::mesh_all(model);
    chunk_rasterizer raster;
    raster.upload(meshes, colours_of(model.palette()));
    dense_grid grid(model);
    tracer<cpu, dense_grid> rays(grid);
    for (int view = 0; view < views; ++view) {
        raster_view v{.cam = auto_camera(model.bounds(), model.up_axis, view), .width = 192, .height = 144,
                      .lod_bias = 64.0f, .to_sun = sun_direction(model.up_axis)};
        raster_frame frame = raster.draw(v);
        auto primary = primary_rays(v.cam, v.width, v.height);
        std::vector<hit> hits(primary.size());
        rays.closest_hit(primary, hits);
        auto a = check::compare_raster_hits(frame.pixels, hits, v.width, v.height);
        SCOPED_TRACE(name + ", view " + std::to_string(view));
        ASSERT_GT(a.covered, 1000u) << "the view shows the model";
        EXPECT_EQ(a.beyond(0.995), 0u) << a.equal << " of " << a.covered << " covered pixels agree";
        EXPECT_EQ(a.off_edges, 0u) << "pixels away from any edge differ";
        EXPECT_GT(frame.draws, 0u);
        int shown = 0;
        bool failed = a.beyond(0.995) > 0 || a.off_edges > 0;
        std::printf("%s, view %d: %llu of %llu covered pixels agree\n", name.c_str(), view,
                    (unsigned long long)a.equal, (unsigned long long)a.covered);
        for (std::size_t i = 0; i < hits.size() && shown < 3 && failed; ++i)
            if (!check::same_surface(frame.pixels[i], hits[i]) && ++shown)
                ADD_FAILURE() << "pixel (" << i % std::size_t(v.width) << ", " << i / std::size_t(v.width)
                              << "): raster voxel (" << frame.pixels[i].voxel.x << ", " << frame.pixels[i].voxel.y
                              << ", " << frame.pixels[i].voxel.z << ") face " << frame.pixels[i].face
                              << ", ray hit voxel (" << hits[i].voxel.x << ", " << hits[i].voxel.y << ", "
                              << hits[i].voxel.z << ") face " << face_name(hits[i].normal) << ", t " << hits[i].t;
    }
}

}  // namespace

TEST(chunk_raster, level_0_shows_the_primary_hits_on_builtin_scenes) {
    expect_raster_matches_rays(scenes::make_chunk_scene("terrain64"), "terrain64", 3);
    // Several chunks, negative coordinates, merged quads with T-junctions.
    expect_raster_matches_rays(test::blob_model(7, box3i{{-70, -20, -90}, {90, 60, 40}}), "blobs", 3);
}

TEST(chunk_raster, level_0_shows_the_primary_hits_on_a_shared_scene) {
    VOXRAY_REQUIRE_DATA();
    auto file = *test::data_dir() / "vox" / "minecraft_tree.vox";
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    expect_raster_matches_rays(io::load_vox(file), "minecraft_tree.vox", 2);
}

TEST(chunk_raster, culling_changes_no_pixel) {
    voxel_model model = test::blob_model(3, box3i{{-64, 0, -64}, {128, 64, 128}});
    chunk_rasterizer raster;
    raster.upload(test::mesh_all(model), colours_of(model.palette()));
    // From inside the model's box, so that chunks lie on every side and behind the eye.
    raster_view v{.cam = look_at({20, 50, 10}, {60, 10, 70}), .width = 160, .height = 120, .lod_bias = 64.0f};
    raster_frame culled = raster.draw(v);
    v.cull_faces = false;
    raster_frame all = raster.draw(v);
    EXPECT_GT(culled.culled, 0u);
    EXPECT_EQ(all.culled, 0u);
    EXPECT_LT(culled.quads, all.quads);
    EXPECT_EQ(culled.rgba, all.rgba);
    std::uint64_t differ = 0;
    for (std::size_t i = 0; i < all.pixels.size(); ++i)
        differ += all.pixels[i].face != culled.pixels[i].face || all.pixels[i].voxel != culled.pixels[i].voxel;
    EXPECT_EQ(differ, 0u);
}

TEST(chunk_raster, coarser_levels_draw_prefixes) {
    voxel_model model = scenes::make_chunk_scene("terrain64");
    chunk_rasterizer raster;
    raster.upload(test::mesh_all(model), colours_of(model.palette()));
    raster_view v{.cam = auto_camera(model.bounds(), model.up_axis), .width = 96, .height = 72, .lod_bias = 64.0f};
    std::uint64_t finest = raster.draw(v).quads;
    v.lod_bias = -8.0f;  // the top level everywhere
    raster_frame coarse = raster.draw(v);
    EXPECT_LT(coarse.quads, finest);
    EXPECT_GT(coarse.quads, 0u);
}

TEST(chunk_raster, an_empty_upload_draws_nothing) {
    chunk_rasterizer raster;
    raster.upload({}, {});
    raster_frame f = raster.draw({.cam = look_at({0, 0, -10}, {0, 0, 0}), .width = 8, .height = 8});
    EXPECT_EQ(f.draws, 0u);
    for (auto& p : f.pixels) EXPECT_EQ(p.face, VX_FACE_NONE);
}

TEST(chunk_raster, bad_sizes_and_order_are_errors) {
    chunk_rasterizer raster;
    raster_view v{.cam = look_at({0, 0, -10}, {0, 0, 0}), .width = 64, .height = 64};
    EXPECT_THROW(
        {
            try {
                raster.draw(v);
            } catch (const error& e) {
                EXPECT_NE(std::string(e.what()).find("no chunks uploaded"), std::string::npos) << e.what();
                throw;
            }
        },
        error);
    raster.upload({}, {});
    v.width = 0;
    EXPECT_THROW(raster.draw(v), error);
    v.width = 1 << 20;
    try {
        raster.draw(v);
        ADD_FAILURE() << "a frame of 2^20 pixels a row was drawn";
    } catch (const error& e) {
        std::string what = e.what();
        EXPECT_NE(what.find("1048576 x 64"), std::string::npos) << what;
        EXPECT_NE(what.find("each side must lie in 1.."), std::string::npos) << what;
    }
}

TEST(chunk_raster, nearer_faces_hide_farther_ones) {
    // Two walls across the view, the nearer one drawn first (a lower chunk index).
    voxel_model model;
    for (int y = -8; y < 8; ++y)
        for (int x = -8; x < 8; ++x) model.set({x, y, -40}, 2), model.set({x, y, 70}, 1);
    chunk_rasterizer raster;
    raster.upload(test::mesh_all(model), colours_of(model.palette()));
    raster_frame f = raster.draw({.cam = look_at({0.5f, 0.5f, -100.0f}, {0.5f, 0.5f, 0.0f}), .width = 16, .height = 16,
                                  .lod_bias = 64.0f});
    const raster_pixel& centre = f.pixels[8 * 16 + 8];
    EXPECT_EQ(centre.face, VX_FACE_NEG_Z);
    EXPECT_EQ(centre.voxel.z, -40);
}

TEST(chunk_raster, fixed_levels_draw_their_prefixes_unmorphed) {
    voxel_model model = test::blob_model(5, box3i{{-40, -40, -40}, {100, 60, 80}});
    auto meshes = test::mesh_all(model);
    chunk_rasterizer raster;
    raster.upload(meshes, colours_of(model.palette()));
    raster_view v{.cam = auto_camera(model.bounds(), model.up_axis), .width = 128, .height = 96, .lod_bias = 64.0f,
                  .cull_faces = false};
    raster_frame by_distance = raster.draw(v);
    v.fixed_level = 0;
    raster_frame fixed = raster.draw(v);
    EXPECT_EQ(fixed.rgba, by_distance.rgba);
    for (int level = 0; level < VX_MESH_LEVELS; ++level) {
        v.fixed_level = level;
        std::uint64_t expected = 0;
        for (auto& m : meshes) expected += m.drawn(level);
        EXPECT_EQ(raster.draw(v).quads, expected) << "level " << level;
    }
    v.fixed_level = VX_MESH_LEVELS;
    EXPECT_THROW(raster.draw(v), error);
}

TEST(triangle_raster, triangles_of_the_quads_draw_the_same_picture) {
    voxel_model model = test::blob_model(9, box3i{{-30, -30, -30}, {90, 50, 70}}, 12, 1);
    auto meshes = test::mesh_all(model);
    std::vector<float> positions;
    std::vector<std::uint32_t> indices;
    for (auto& m : meshes)
        meshing::for_each_quad_at(m, 0, [&](std::uint32_t, const std::array<glm::ivec3, 4>& quad) {
            auto base = std::uint32_t(positions.size() / 3);
            for (auto& p : quad) positions.insert(positions.end(), {float(p.x), float(p.y), float(p.z)});
            indices.insert(indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
        });
    constexpr std::uint32_t grey = 0xFFB4B4B4u;
    chunk_rasterizer quads;
    quads.upload(meshes, std::vector<std::uint32_t>(palette::size, grey));
    triangle_rasterizer triangles;
    triangles.upload(positions, indices, grey);
    raster_view v{.cam = auto_camera(model.bounds(), model.up_axis, 2), .width = 160, .height = 120,
                  .lod_bias = 64.0f, .to_sun = sun_direction(model.up_axis)};
    raster_frame a = quads.draw(v), b = triangles.draw(v);
    EXPECT_EQ(b.triangles, indices.size() / 3);
    std::uint64_t covered = 0, coverage_differs = 0, colour_differs = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        bool in_a = a.rgba[4 * i + 3] != 0, in_b = b.rgba[4 * i + 3] != 0;
        covered += in_a;
        coverage_differs += in_a != in_b;
        EXPECT_EQ(in_b, b.pixels[i].face == VX_FACE_INSIDE);
        for (std::size_t k = 0; k < 3 && in_a && in_b; ++k)
            colour_differs += std::abs(int(a.rgba[4 * i + k]) - int(b.rgba[4 * i + k])) > 2;
    }
    EXPECT_GT(covered, 2000u);
    EXPECT_EQ(coverage_differs, 0u);
    EXPECT_EQ(colour_differs, 0u);
}

TEST(triangle_raster, bad_meshes_are_errors) {
    triangle_rasterizer raster;
    std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    try {
        raster.upload(positions, std::vector<std::uint32_t>{0, 1, 3}, 0xFFFFFFFFu);
        ADD_FAILURE() << "an index beyond the vertices was taken";
    } catch (const error& e) {
        EXPECT_NE(std::string(e.what()).find("index 2 is 3, beyond the 3 vertices"), std::string::npos) << e.what();
    }
    EXPECT_THROW(raster.upload(positions, std::vector<std::uint32_t>{0, 1}, 0u), error);
    EXPECT_THROW(raster.draw({.cam = look_at({0, 0, -5}, {0, 0, 0}), .width = 8, .height = 8}), error);
}
