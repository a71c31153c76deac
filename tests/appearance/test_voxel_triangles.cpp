// A voxel's own triangles (appearance/voxel_triangles.hpp) against Embree's BVH: the same
// first hits for rays inside voxels, the same tables from the precompute either way, and the
// whole scene kept where too many triangles reach a voxel.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "test_data.hpp"
#include "voxray/appearance/precompute.hpp"
#include "voxray/embree/triangle_scene.hpp"
#include "voxray/gltf/coloured_mesh.hpp"

namespace voxray {
namespace {

// Voxel space is world space: origin 0, one voxel a unit.
io::voxel_grid_map unit_voxel_grid() {
    io::voxel_grid_map g;
    g.dims = {32, 32, 32};
    return g;
}

// A UV sphere of radius 6 about (10, 10, 10) (48 triangles meet at each pole), and a plane lying exactly on voxel faces
// (z = 3) where rays start on the surface itself.
io::triangle_mesh sphere_and_plane() {
    io::triangle_mesh m;
    const int rings = 24, segments = 48;
    for (int i = 0; i <= rings; ++i)
        for (int j = 0; j < segments; ++j) {
            double theta = std::numbers::pi * i / rings, phi = 2.0 * std::numbers::pi * j / segments;
            glm::dvec3 unit(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
            m.positions.push_back(glm::dvec3(10) + 6.0 * unit);
        }
    for (std::uint32_t i = 0; i < rings; ++i)
        for (std::uint32_t j = 0; j < segments; ++j) {
            std::uint32_t a = i * segments + j, b = i * segments + (j + 1) % segments;
            m.triangles.push_back({a, a + segments, b});
            m.triangles.push_back({b, a + segments, b + segments});
        }
    auto base = std::uint32_t(m.positions.size());
    for (glm::dvec3 p : {glm::dvec3{2, 2, 3}, glm::dvec3{8, 2, 3}, glm::dvec3{8, 8, 3}, glm::dvec3{2, 8, 3}})
        m.positions.push_back(p);
    m.triangles.push_back({base, base + 1, base + 2});
    m.triangles.push_back({base, base + 2, base + 3});
    m.group_names = {"sphere and plane"};
    return m;
}

// Every first hit of a voxel's sampling and opacity-like rays, as first_surface asks for
// them (from just outside the entry face to just past the exit), is Embree's: the same
// triangle, t, weights and normal, up to float rounding.
TEST(appearance_voxel_triangles, first_hits_are_embrees) {
    io::triangle_mesh m = sphere_and_plane();
    embree::triangle_scene scene(m, unit_voxel_grid());
    appearance::voxel_triangles near;
    std::size_t rays = 0, hits = 0, same = 0, voxels = 0, crowded = 0;
    for (int z = 0; z < 20; ++z)
        for (int y = 0; y < 20; ++y)
            for (int x = 0; x < 20; ++x) {
                glm::ivec3 v(x, y, z);
                if (!near.gather(scene, v)) {  // the poles' fans: those voxels keep the scene
                    ++crowded;
                    continue;
                }
                if (near.size() == 0) continue;  // no surface: a voxel the voxelizer leaves empty
                ++voxels;
                appearance::voxel_rays source(v, 64, false, 3);
                for (std::uint32_t i = 0; i < 64; ++i, ++rays) {
                    appearance::sampling_ray r = source(i);
                    const float margin = 1e-4f;
                    glm::vec3 dir(r.direction), org = glm::vec3(r.origin) - margin * dir;
                    float tfar = float(r.length) + 2.0f * margin;
                    auto mine = near.first_hit(org, dir, 0.0f, tfar);
                    auto theirs = scene.first_hit(org, dir, 0.0f, tfar);
                    ASSERT_EQ(bool(mine), bool(theirs)) << "voxel " << x << ", " << y << ", " << z << " ray " << i;
                    if (!mine) continue;
                    ++hits;
                    if (mine->triangle != theirs->triangle) continue;  // a shared edge: either is right
                    ++same;
                    EXPECT_NEAR(mine->t, theirs->t, 2e-4f);
                    for (int k = 0; k < 3; ++k) {
                        EXPECT_NEAR(mine->barycentric[k], theirs->barycentric[k], 2e-4);
                        EXPECT_NEAR(mine->normal[k], theirs->normal[k], 1e-5f);
                    }
                }
            }
    std::printf("%zu voxels (and %zu crowded), %zu rays, %zu hits, %zu on Embree's triangle\n", voxels, crowded,
                rays, hits, same);
    EXPECT_GT(voxels, 500u);
    EXPECT_LE(crowded, 16u);
    EXPECT_GT(hits, rays / 6);  // a surface cuts a fifth of the rays through its voxels
    EXPECT_GE(double(same), 0.998 * double(hits));
}

// Eighty triangles fanned through one voxel: over the list's limit, so the voxel keeps
// tracing the whole scene, and its record is the one Embree's BVH gives.
TEST(appearance_voxel_triangles, a_crowded_voxel_keeps_the_scene) {
    io::triangle_mesh m;
    for (int k = 0; k < 80; ++k) {
        double a = std::numbers::pi * k / 80;
        auto base = std::uint32_t(m.positions.size());
        glm::dvec3 c(4.5, 4.5, 4.5), d(std::cos(a), std::sin(a), 0.0);
        for (glm::dvec3 p : {c - 2.0 * d + glm::dvec3(0, 0, -2), c + 2.0 * d + glm::dvec3(0, 0, -2),
                             c + glm::dvec3(0, 0, 2)})
            m.positions.push_back(p);
        m.triangles.push_back({base, base + 1, base + 2});
    }
    m.group_names = {"fan"};
    embree::triangle_scene scene(m, unit_voxel_grid());
    appearance::voxel_triangles near;
    EXPECT_FALSE(near.gather(scene, {4, 4, 4}));
    voxel_model model;
    model.set({4, 4, 4}, 1);
    for (auto kind : {appearance::record_kind::averages, appearance::record_kind::compact}) {
        auto table = [&](bool lists) {
            return appearance::precompute(scene, m, model, {.kind = kind, .threads = 1, .voxel_lists = lists});
        };
        appearance::appearance_table listed = table(true), traced = table(false);
        EXPECT_EQ(listed.words, traced.words);
        EXPECT_EQ(listed.faces, traced.faces);
    }
}

// A shared coloured scene (textures, cut-out leaves): the tables through the voxels' lists
// and through Embree's BVH agree, up to rays that graze a shared edge.
TEST(appearance_voxel_triangles, the_tables_agree_with_embrees_on_a_shared_scene) {
    VOXRAY_REQUIRE_DATA();
    io::triangle_mesh mesh = gltf::load_coloured_mesh(*test::data_dir() / "mesh" / "small_tree" / "scene.gltf");
    const int resolution = 32;
    voxel_model model = io::voxelize(mesh, {.resolution = resolution, .threads = 2});
    embree::triangle_scene scene(mesh, io::make_grid_map(mesh.bounds(), resolution));
    auto table = [&](bool lists) {
        return appearance::precompute(scene, mesh, model, {.threads = 2, .voxel_lists = lists});
    };
    appearance::appearance_table listed = table(true), traced = table(false);
    ASSERT_EQ(listed.size(), traced.size());
    std::size_t differ = 0;
    int worst = 0;
    for (std::size_t row = 0; row < listed.size(); ++row) {
        auto a = listed.record(row), b = traced.record(row);
        int d = std::abs(int(VX_APP_AVG_OPACITY(a[0])) - int(VX_APP_AVG_OPACITY(b[0])));
        for (auto channel : {VX_APP_AVG_R(a[0]) - int(VX_APP_AVG_R(b[0])), VX_APP_AVG_G(a[0]) - int(VX_APP_AVG_G(b[0])),
                             VX_APP_AVG_B(a[0]) - int(VX_APP_AVG_B(b[0]))})
            d = std::max(d, std::abs(int(channel)));
        differ += d > 0 ? 1 : 0;
        worst = std::max(worst, d);
    }
    std::printf("small tree at %d: %zu voxels, %zu records differ, by %d codes at most\n", resolution, listed.size(),
                differ, worst);
    EXPECT_LE(double(differ), 0.02 * double(listed.size()));
    EXPECT_LE(worst, 2);
}

}  // namespace
}  // namespace voxray
