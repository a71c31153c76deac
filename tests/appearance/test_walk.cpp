// The compositing walk (appearance/walk.inc) on the CPU's scalar lanes over the dense grid:
// opaque records stop it at the first-hit kernel's voxel; faint records blend every voxel
// on the ray exactly once, touching voxels of one sheet adding their coverage, voxels apart
// or turned apart as layers; a voxel with no record is an error that names it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "walk_tables.hpp"
#include "voxray/brickmap/brickmap.hpp"
#include "voxray/cpu/appearance_walk.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/naadf/naadf.hpp"
#include "voxray/rays/camera.hpp"
#include "voxray/scenes/builtin.hpp"

namespace voxray {
namespace {

using namespace appearance;
using test::uniform_table;
using test::camera_rays;

TEST(appearance_walk, opaque_records_stop_at_the_first_hit_kernels_voxel) {
    voxel_model model = scenes::make_builtin("noise50");
    dense_grid grid(model);
    std::vector<std::uint32_t> blob(grid.blob().begin(), grid.blob().end());
    appearance_walker<kernels::dense_grid_kernel> walker(blob, uniform_table(model, 15), 2);
    std::vector<ray> rays = camera_rays(model, 48);
    std::vector<appearance_pixel> out = walker.walk(rays, {});
    std::size_t hits = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        const ray& r = rays[i];
        kernels::scalar::vx_ray lane{r.origin.x, r.origin.y, r.origin.z, r.tmin,
                                     r.direction.x, r.direction.y, r.direction.z, r.tmax};
        auto h = kernels::scalar::kernel_lanes<kernels::dense_grid_kernel>::trace<VX_MODE_CLOSEST>(blob.data(), lane);
        ASSERT_EQ(out[i].status, h.status) << i;
        if (h.status != VX_STATUS_HIT) {
            EXPECT_EQ(out[i].visits, 0u);
            EXPECT_EQ(out[i].transmittance, 1.0f);
            continue;
        }
        ++hits;
        EXPECT_EQ(glm::ivec3(out[i].x, out[i].y, out[i].z), glm::ivec3(h.x, h.y, h.z));
        EXPECT_EQ(out[i].t, h.t);
        EXPECT_EQ(out[i].face, h.face);
        EXPECT_EQ(out[i].visits, 1u);
        EXPECT_EQ(out[i].transmittance, 0.0f);
    }
    EXPECT_GT(hits, rays.size() / 4);
}

// The voxels a ray crosses inside [0, n)^3 (each for longer than `sliver`), in double.
int crossed_voxels(const ray& r, int n, double sliver) {
    glm::dvec3 o(r.origin), d(r.direction);
    double t0 = 0, t1 = 1e30;
    for (int a = 0; a < 3; ++a) {
        double ta = (0 - o[a]) / d[a], tb = (n - o[a]) / d[a];
        t0 = std::max(t0, std::min(ta, tb)), t1 = std::min(t1, std::max(ta, tb));
    }
    std::vector<double> cuts{t0, t1};
    for (int a = 0; a < 3; ++a)
        for (int c = 1; c < n; ++c) {
            double t = (c - o[a]) / d[a];
            if (t > t0 && t < t1) cuts.push_back(t);
        }
    std::sort(cuts.begin(), cuts.end());
    int count = 0;
    for (std::size_t i = 1; i < cuts.size(); ++i) count += cuts[i] - cuts[i - 1] > sliver ? 1 : 0;
    return count;
}

TEST(appearance_walk, faint_records_blend_every_voxel_on_the_ray_once) {
    voxel_model block;
    const int n = 8;
    for (int z = 0; z < n; ++z)
        for (int y = 0; y < n; ++y)
            for (int x = 0; x < n; ++x) block.set({x, y, z}, 1);
    dense_grid grid(block);
    appearance_table table = uniform_table(block, 1);  // opacity 1/15
    appearance_walker<kernels::dense_grid_kernel> walker({grid.blob().begin(), grid.blob().end()}, table, 2);
    std::mt19937_64 g(7);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<ray> rays;
    for (int i = 0; i < 2000; ++i) {
        glm::vec3 target(4 + 3.5f * u(g), 4 + 3.5f * u(g), 4 + 3.5f * u(g));
        glm::vec3 from = target + 20.0f * glm::normalize(glm::vec3(u(g), u(g), u(g)));
        rays.push_back({from, 0.0f, glm::normalize(target - from), 1e30f});
    }
    rays.push_back({{0.5f, 0.5f, -3.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, 1e30f});  // straight down a column
    std::vector<appearance_pixel> out = walker.walk(rays, {.cutoff = 0.0f});
    const float a = 1.0f / 15.0f;
    int equal = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        int want = crossed_voxels(rays[i], n, 1e-5);
        equal += int(out[i].visits) == want ? 1 : 0;
        // One run of touching voxels: their coverages add up.
        EXPECT_NEAR(out[i].transmittance, std::max(0.0f, 1.0f - a * float(out[i].visits)), 1e-5f);
    }
    EXPECT_EQ(out.back().visits, 8u);
    EXPECT_GE(equal, int(rays.size()) - 5) << "rays whose voxels were each blended once";
    // Down the column every voxel has the same colour c, and each adds a c in full: 8 a c.
    kernels::scalar::vx_app_light light{0.0f, 0.0f, -1.0f, 0.25f};
    auto one = kernels::scalar::vx_app_compact_sample(table.words.data(), table.faces.data(), 0u, 0, 0, 1, light);
    appearance_light down{.to_light = {0, 0, -1}, .ambient = 0.25f, .cutoff = 0.0f};
    std::vector<appearance_pixel> column = walker.walk(std::span(rays).last(1), down);
    EXPECT_NEAR(column[0].r, 8.0f * a * one.r, 1e-6f);
}

// Written once for every structure: over the brickmap and NAADF the walk meets the same
// voxels as over the dense grid, so it blends the same colours, bit for bit.
TEST(appearance_walk, every_structure_gives_the_same_pixels) {
    voxel_model model = scenes::make_builtin("noise50");
    appearance_table table = uniform_table(model, 5);
    std::vector<ray> rays = camera_rays(model, 40);
    appearance_light light{.to_light = glm::normalize(glm::vec3(1, 2, 3)), .ambient = 0.2f, .cutoff = 1e-3f};
    auto words = [](std::span<const std::uint32_t> b) { return std::vector<std::uint32_t>(b.begin(), b.end()); };
    using kernels::brickmap_kernel, kernels::dense_grid_kernel, kernels::naadf_kernel;
    auto dense = appearance_walker<dense_grid_kernel>(words(dense_grid(model).blob()), table, 2).walk(rays, light);
    auto bricks = appearance_walker<brickmap_kernel>(words(brickmap<>(model).blob()), table, 2).walk(rays, light);
    auto fields = appearance_walker<naadf_kernel>(words(naadf(model).blob()), table, 2).walk(rays, light);
    std::size_t blended = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        for (const auto* other : {&bricks[i], &fields[i]}) {
            EXPECT_EQ(other->visits, dense[i].visits) << i;
            EXPECT_EQ(glm::vec4(other->r, other->g, other->b, other->transmittance),
                      glm::vec4(dense[i].r, dense[i].g, dense[i].b, dense[i].transmittance)) << i;
        }
        blended += dense[i].visits > 1 ? 1u : 0u;
    }
    EXPECT_GT(blended, rays.size() / 10);  // rays that blend several voxels, not only first hits
}

// The ray goes on from a voxel into the next face to face: one visit blends the whole run of
// touching voxels (a DDA step each, no closest hit), and the ray leaves the run's last voxel.
// A run that ends at an empty voxel, or where the ray leaves through an edge, re-enters.
TEST(appearance_walk, one_closest_hit_blends_a_run_of_touching_voxels) {
    voxel_model model;
    for (int z = 0; z < 5; ++z) model.set({1, 1, z}, 1);  // a column of 5 voxels
    model.set({1, 1, 7}, 1);                               // one apart, after an empty gap
    model.set({2, 1, 7}, 1);                               // beside it, face to face
    model.set({2, 2, 7}, 1);                               // touching it by an edge only
    walk_words words(uniform_table(model, 1));             // opacity 1/15: nothing stops the walk
    namespace k = kernels::scalar;
    k::vx_app_light light{0.0f, 0.0f, -1.0f, 0.25f};
    auto visit = [&](k::vx_ray r, k::vx_hit h) {
        k::vx_app_walk_cursor c = k::vx_app_walk_begin(r, k::vx_app_walk_state_start(), 64u);
        return k::vx_app_walk_visit(words.index.data(), words.records.data(), words.faces.data(), words.kind, light,
                                    0.0f, 64u, 0u, h, c);
    };
    // Down the column from z = -3: the closest hit is voxel (1, 1, 0) at t = 3.
    k::vx_ray down{1.5f, 1.5f, -3.0f, 0.0f, 0.0f, 0.0f, 1.0f, 1e30f};
    k::vx_app_walk_cursor c = visit(down, {3.0f, 1, 1, 0, VX_FACE_NONE, 1u, 2u, VX_STATUS_HIT});
    EXPECT_EQ(c.s.w.visits, 5u);
    EXPECT_EQ(glm::ivec3(c.s.px, c.s.py, c.s.pz), glm::ivec3(1, 1, 4));
    EXPECT_EQ(c.s.w.steps, 2u + 4u);  // the closest hit's steps, then a step a voxel
    EXPECT_EQ(c.r.tmin, 8.0f + 8.0f * 1e-6f);  // just past the far face of (1, 1, 4): z = 5
    EXPECT_EQ(c.going, 1u);                     // on to the closest hit past the gap
    EXPECT_NEAR(c.s.w.transmittance, 1.0f - 5.0f / 15.0f, 1e-6f);  // one run: coverages add up
    // Through (1, 1, 7) towards +x+y, leaving it exactly through the edge it shares with
    // (2, 2, 7): not through a face, so no step (not even into (2, 1, 7), whose face the ray
    // only grazes at that edge); the walk re-enters there.
    k::vx_ray diagonal{1.0f, 1.0f, 7.5f, 0.0f, 0.70710678f, 0.70710678f, 0.0f, 1e30f};
    c = visit(diagonal, {0.0f, 1, 1, 7, VX_FACE_NONE, 1u, 0u, VX_STATUS_HIT});
    EXPECT_EQ(c.s.w.visits, 1u);
    EXPECT_EQ(c.going, 1u);
}

// A re-entry starts just past the exit of the voxel it left, so it does not land back in
// that voxel: down the column from above (-z, where the entry point at a face lies in the
// voxel just left), the walk takes one closest hit per run and one past the last.
TEST(appearance_walk, a_re_entry_takes_one_closest_hit) {
    voxel_model model;
    for (int z = 0; z < 5; ++z) model.set({1, 1, z}, 1);
    model.set({1, 1, 7}, 1);
    dense_grid grid(model);
    std::vector<std::uint32_t> blob(grid.blob().begin(), grid.blob().end());
    walk_words words(uniform_table(model, 1));
    namespace k = kernels::scalar;
    k::vx_app_walk_cursor c =
        k::vx_app_walk_begin({1.5f, 1.5f, 12.0f, 0.0f, 0.0f, 0.0f, -1.0f, 1e30f}, k::vx_app_walk_state_start(), 64u);
    while (c.going != 0u) {
        k::vx_hit h = k::kernel_lanes<kernels::dense_grid_kernel>::trace<VX_MODE_CLOSEST>(blob.data(), c.r);
        c = k::vx_app_walk_visit(words.index.data(), words.records.data(), words.faces.data(), words.kind,
                                 {0.0f, 0.0f, 1.0f, 0.25f}, 0.0f, 64u, 0u, h, c);
    }
    EXPECT_EQ(c.s.w.visits, 6u);
    EXPECT_EQ(c.tries, 3u);  // (1, 1, 7); the column's top after the gap; past its bottom: a miss
}

// Voxels apart along a ray are separate layers: T = (1 - a)^2, C = a c + (1 - a) a c.
TEST(appearance_walk, voxels_apart_blend_as_independent_layers) {
    voxel_model two;
    two.set({0, 0, 0}, 1);
    two.set({0, 0, 2}, 1);
    dense_grid grid(two);
    appearance_table table = uniform_table(two, 6);
    appearance_walker<kernels::dense_grid_kernel> walker({grid.blob().begin(), grid.blob().end()}, table, 1);
    std::vector<ray> column{{{0.5f, 0.5f, -3.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, 1e30f}};
    appearance_light down{.to_light = {0, 0, -1}, .ambient = 0.25f, .cutoff = 0.0f};
    appearance_pixel p = walker.walk(column, down)[0];
    kernels::scalar::vx_app_light light{0.0f, 0.0f, -1.0f, 0.25f};
    auto one = kernels::scalar::vx_app_compact_sample(table.words.data(), table.faces.data(), 0u, 0, 0, 1, light);
    EXPECT_EQ(p.visits, 2u);
    EXPECT_NEAR(p.transmittance, (1 - one.a) * (1 - one.a), 1e-6f);
    EXPECT_NEAR(p.r, one.a * one.r + (1 - one.a) * one.a * one.r, 1e-6f);
}

// Touching voxels make one run only while they show one sheet: a surface turned 60 degrees
// from the last voxel's is a layer of its own (foliage), one turned 10 degrees the same sheet.
TEST(appearance_walk, touching_voxels_turned_apart_blend_as_independent_layers) {
    voxel_model two;
    two.set({0, 0, 0}, 1);
    two.set({0, 0, 1}, 1);
    dense_grid grid(two);
    std::vector<ray> column{{{0.5f, 0.5f, -3.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, 1e30f}};
    appearance_light down{.to_light = {0, 0, -1}, .ambient = 0.25f, .cutoff = 0.0f};
    auto walk_turned = [&](float degrees) {
        appearance_table table = uniform_table(two, 6);  // opacity 6/15 each
        const float turn = glm::radians(degrees);
        glm::vec2 e = octahedral({std::sin(turn), 0.0f, -std::cos(turn)});
        // row 1 (voxel (0, 0, 1)) has one face, face 1: its word 1 holds the normal
        table.faces[VX_APP_FACE_WORDS * 1 + 1] = VX_APP_FACE_WORD1(snorm(e.x, 12), snorm(e.y, 12), 0u);
        appearance_walker<kernels::dense_grid_kernel> walker({grid.blob().begin(), grid.blob().end()}, table, 1);
        return walker.walk(column, down)[0];
    };
    const float a = 6.0f / 15.0f;
    appearance_pixel sheet = walk_turned(10.0f), leaves = walk_turned(60.0f);
    EXPECT_EQ(sheet.visits, 2u);
    EXPECT_EQ(leaves.visits, 2u);
    EXPECT_NEAR(sheet.transmittance, 1.0f - 2.0f * a, 1e-6f);
    EXPECT_NEAR(leaves.transmittance, (1.0f - a) * (1.0f - a), 1e-6f);
}

TEST(appearance_walk, a_voxel_without_a_record_is_an_error_that_names_it) {
    voxel_model model;
    model.set({2, 3, 4}, 1);
    model.set({2, 3, 9}, 1);
    voxel_model fewer;
    fewer.set({2, 3, 4}, 1);
    dense_grid grid(model);
    appearance_walker<kernels::dense_grid_kernel> walker({grid.blob().begin(), grid.blob().end()},
                                                         uniform_table(fewer, 4), 1);
    std::vector<ray> rays{{{2.5f, 3.5f, 0.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, 1e30f}};
    try {
        walker.walk(rays, {});
        FAIL() << "no error";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("(2, 3, 9)"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace voxray
