// The public ray helpers (voxray/rays.hpp): cameras, primary, shadow and diffuse rays,
// hit-point offsetting, and the inactive rays that keep batches index-aligned.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "random_models.hpp"
#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/rays.hpp"

using namespace voxray;

namespace {

TEST(RayHelpers, PrimaryRayIsThePixelOfPrimaryRays) {
    camera c = look_at({-10, 20, -30}, {4, 5, 6}, 40.0f);
    auto rays = primary_rays(c, 7, 5);
    for (int y = 0; y < 5; ++y)
        for (int x = 0; x < 7; ++x) {
            ray r = primary_ray(c, x, y, 7, 5);
            EXPECT_EQ(r.origin, rays[y * 7 + x].origin);
            EXPECT_EQ(r.direction, rays[y * 7 + x].direction);
        }
    // The centre pixel looks at the target; row 0 is the top of the image.
    glm::vec3 forward = glm::normalize(c.target - c.position);
    EXPECT_NEAR(glm::dot(rays[2 * 7 + 3].direction, forward), 1.0f, 1e-6f);
    EXPECT_GT(rays[3].direction.y, rays[4 * 7 + 3].direction.y);
}

// Tiles: every pixel once (edge tiles cut to the picture), 8x8 tiles row-major, Z order
// inside a tile, and each ray the one of its pixel.
TEST(RayHelpers, TiledPrimaryRaysVisitEveryPixelOnceInZOrder) {
    const int w = 19, h = 11;
    camera c = look_at({-10, 20, -30}, {4, 5, 6}, 40.0f);
    auto order = pixel_sequence(w, h, pixel_order::tiles);
    auto rays = primary_rays(c, w, h, pixel_order::tiles);
    ASSERT_EQ(order.size(), std::size_t(w * h));
    ASSERT_EQ(rays.size(), order.size());
    std::vector<int> seen(w * h, 0);
    for (std::size_t i = 0; i < order.size(); ++i) {
        ASSERT_TRUE(order[i].x >= 0 && order[i].x < w && order[i].y >= 0 && order[i].y < h) << i;
        ++seen[order[i].y * w + order[i].x];
        ray r = primary_ray(c, order[i].x, order[i].y, w, h);
        EXPECT_EQ(r.direction, rays[i].direction) << i;
    }
    for (int n : seen) EXPECT_EQ(n, 1);
    // The first tile is whole: Z order, 2x2 quads, then 4x4 blocks.
    std::vector<glm::ivec2> first{order.begin(), order.begin() + 6};
    EXPECT_EQ(first, (std::vector<glm::ivec2>{{0, 0}, {1, 0}, {0, 1}, {1, 1}, {2, 0}, {3, 0}}));
    EXPECT_EQ(order[15], glm::ivec2(3, 3));
    EXPECT_EQ(order[63], glm::ivec2(7, 7));
    EXPECT_EQ(order[64], glm::ivec2(8, 0));  // the next tile along the row
    EXPECT_EQ(pixel_sequence(w, h, pixel_order::rows)[20], glm::ivec2(1, 1));
}

TEST(RayHelpers, LookAtStraightDownStillHasAnUp) {
    camera c = look_at({0, 50, 0}, {0, 0, 0}, 50.0f);  // along the default up (Y)
    auto rays = primary_rays(c, 4, 4);
    for (const ray& r : rays) EXPECT_FALSE(std::isnan(r.direction.x) || std::isnan(r.direction.y) || std::isnan(r.direction.z));
}

TEST(RayHelpers, ShadowAndDiffuseRaysLeaveTheHitFace) {
    voxel_model model = test::solid_block({0, 0, 0}, {16, 4, 16});  // a floor, top at y = 4
    dense_grid grid(model);
    tracer<cpu, dense_grid> t(grid);
    auto rays = primary_rays(look_at({8, 30, -20}, {8, 0, 8}), 32, 32);
    std::vector<hit> hits(rays.size());
    t.closest_hit(rays, hits);
    glm::vec3 sun{0.3f, 1.0f, 0.2f};
    auto shadow = shadow_rays(rays, hits, sun);
    auto bounce = diffuse_rays(rays, hits, 3);
    std::vector<hit> shadow_hits(rays.size()), bounce_hits(rays.size());
    t.any_hit(shadow, shadow_hits);
    t.closest_hit(bounce, bounce_hits);
    int surfaces = 0, tops = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (!has_surface(hits[i])) {
            // Misses get inactive rays, which every backend skips: a miss, no steps.
            EXPECT_GT(shadow[i].tmin, shadow[i].tmax);
            EXPECT_FALSE(shadow_hits[i].is_hit());
            EXPECT_EQ(shadow_hits[i].steps, 0u);
            continue;
        }
        ++surfaces;
        glm::vec3 n = face_normal(hits[i].normal);
        glm::vec3 p = offset_hit_point(rays[i], hits[i]);
        glm::ivec3 cell(glm::floor(p));
        EXPECT_EQ(cell, hits[i].voxel + glm::ivec3(n)) << "the offset point is not in the voxel in front of the face";
        EXPECT_NEAR(glm::length(bounce[i].direction), 1.0f, 1e-5f);
        EXPECT_GT(glm::dot(bounce[i].direction, n), 0.0f) << "a diffuse bounce goes into the surface";
        // Nothing above the open top: neither the sun nor a bounce from there hits anything.
        // (From a side face the sun, which points into the block, is blocked.)
        if (hits[i].normal == face::pos_y) {
            ++tops;
            EXPECT_FALSE(shadow_hits[i].is_hit());
            EXPECT_FALSE(bounce_hits[i].is_hit());
        } else if (hits[i].normal == face::neg_z) {
            EXPECT_TRUE(shadow_hits[i].is_hit());
        }
    }
    EXPECT_GT(tops, 100);
}

TEST(RayHelpers, DiffuseRaysAreSeeded) {
    ray r{{0.5f, 10.0f, 0.5f}, 0.0f, {0, -1, 0}, INFINITY};
    hit h;
    h.t = 6.0f;
    h.voxel = {0, 3, 0};
    h.normal = face::pos_y;
    h.status = VX_STATUS_HIT;
    std::vector<ray> one(5, r);
    std::vector<hit> hits(5, h);
    auto a = diffuse_rays(one, hits, 11), b = diffuse_rays(one, hits, 11), c = diffuse_rays(one, hits, 12);
    for (int i = 0; i < 5; ++i) EXPECT_EQ(a[i].direction, b[i].direction);
    EXPECT_NE(a[0].direction, c[0].direction);
}

}  // namespace
