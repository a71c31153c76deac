// The edge-case ray suite on the reference grid: every face, starts inside solid and
// outside the world, axis-parallel and zero/negative components, tmin/tmax clipping,
// infinite tmax, NaN/Inf rays, and large coordinates. Run on both CPU lane sets.
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"

using namespace voxray;

namespace {

template <class Backend>
struct edge_cases : ::testing::Test {
    hit trace(const voxel_model& m, ray r) {
        dense_grid grid(m);
        tracer<Backend, dense_grid> t(grid);
        hit h;
        t.closest_hit({&r, 1}, {&h, 1});
        return h;
    }
    ray make(glm::vec3 o, glm::vec3 d, float tmin = 0.0f, float tmax = INFINITY) { return {o, tmin, d, tmax}; }
};

using backends = ::testing::Types<cpu, cpu_scalar>;
TYPED_TEST_SUITE(edge_cases, backends);

voxel_model single(glm::ivec3 p, std::uint8_t m = 7) {
    voxel_model model;
    model.set(p, m);
    return model;
}

TYPED_TEST(edge_cases, hits_every_face_with_the_right_normal) {
    auto m = single({3, 4, 5});
    glm::vec3 c(3.5f, 4.5f, 5.5f);
    struct { glm::vec3 dir; face f; } cases[] = {
        {{1, 0, 0}, face::neg_x}, {{-1, 0, 0}, face::pos_x}, {{0, 1, 0}, face::neg_y},
        {{0, -1, 0}, face::pos_y}, {{0, 0, 1}, face::neg_z}, {{0, 0, -1}, face::pos_z}};
    for (auto& k : cases) {
        hit h = this->trace(m, this->make(c - k.dir * 10.0f, k.dir));
        ASSERT_TRUE(h.is_hit());
        EXPECT_EQ(h.normal, k.f) << face_name(h.normal);
        EXPECT_EQ(h.voxel, glm::ivec3(3, 4, 5));
        EXPECT_EQ(h.material, 7u);
        EXPECT_FLOAT_EQ(h.t, 9.5f);
    }
}

TYPED_TEST(edge_cases, start_inside_solid_hits_at_tmin) {
    auto m = single({0, 0, 0});
    hit h = this->trace(m, this->make({0.25f, 0.5f, 0.75f}, {1, 1, 0}, 0.1f));
    ASSERT_TRUE(h.is_hit());
    EXPECT_EQ(h.normal, face::inside);
    EXPECT_FLOAT_EQ(h.t, 0.1f);
}

TYPED_TEST(edge_cases, clipped_by_tmin_and_tmax) {
    voxel_model m;
    m.set({2, 0, 0}, 1);
    m.set({6, 0, 0}, 2);
    auto r = this->make({0.0f, 0.5f, 0.5f}, {1, 0, 0});
    EXPECT_EQ(this->trace(m, r).voxel.x, 2);
    r.tmin = 3.0f;  // skips the first voxel
    EXPECT_EQ(this->trace(m, r).voxel.x, 6);
    r.tmax = 5.5f;  // ends before the second
    EXPECT_FALSE(this->trace(m, r).is_hit());
    r.tmax = 6.0f;  // touches its face exactly
    EXPECT_TRUE(this->trace(m, r).is_hit());
}

TYPED_TEST(edge_cases, negative_and_zero_components) {
    voxel_model m;
    m.set({-5, -6, -7}, 3);
    auto h = this->trace(m, this->make({-4.5f, 10.0f, -6.5f}, {0, -2, 0}));
    ASSERT_TRUE(h.is_hit());
    EXPECT_EQ(h.voxel, glm::ivec3(-5, -6, -7));
    EXPECT_EQ(h.normal, face::pos_y);
    EXPECT_FLOAT_EQ(h.t, (10.0f - -5.0f) / 2.0f);
    // A ray parallel to an axis, outside the voxel's slab, misses.
    EXPECT_FALSE(this->trace(m, this->make({-3.5f, 10.0f, -6.5f}, {0, -1, 0})).is_hit());
}

TYPED_TEST(edge_cases, ray_along_a_face_plane) {
    auto m = single({0, 0, 0});
    // Origin on the plane x = 1 (the voxel's +x face), moving along it: never inside.
    EXPECT_FALSE(this->trace(m, this->make({1.0f, -3.0f, 0.5f}, {0, 1, 0})).is_hit());
    // On the plane x = 0: cells are [0, 1), so this ray runs inside the voxel's slab.
    EXPECT_TRUE(this->trace(m, this->make({0.0f, -3.0f, 0.5f}, {0, 1, 0})).is_hit());
}

TYPED_TEST(edge_cases, invalid_rays_miss) {
    auto m = single({0, 0, 0});
    float nan = std::numeric_limits<float>::quiet_NaN(), inf = INFINITY;
    ray bad[] = {this->make({nan, 0.5f, 0.5f}, {1, 0, 0}), this->make({-1, 0.5f, 0.5f}, {nan, 0, 0}),
                 this->make({-inf, 0.5f, 0.5f}, {1, 0, 0}), this->make({-1, 0.5f, 0.5f}, {inf, 0, 0}),
                 this->make({-1, 0.5f, 0.5f}, {1, 0, 0}, nan), this->make({-1, 0.5f, 0.5f}, {1, 0, 0}, 0.0f, nan),
                 this->make({-1, 0.5f, 0.5f}, {0, 0, 0}), this->make({-1, 0.5f, 0.5f}, {1, 0, 0}, 5.0f, 1.0f)};
    for (auto& r : bad) {
        hit h = this->trace(m, r);
        EXPECT_FALSE(h.is_hit());
        EXPECT_EQ(h.normal, face::none);
        EXPECT_EQ(h.material, 0u);
    }
}

TYPED_TEST(edge_cases, far_away_origin_and_infinite_tmax) {
    auto m = single({100, 100, 100});
    auto h = this->trace(m, this->make({100.5f, 100.5f, -60000.0f}, {0, 0, 1}));
    ASSERT_TRUE(h.is_hit());
    EXPECT_EQ(h.voxel, glm::ivec3(100, 100, 100));
    EXPECT_NEAR(h.t, 60100.0f, 0.01f);
}

TYPED_TEST(edge_cases, large_world_coordinates) {
    voxel_model m;
    m.set({65000, 3, 65000}, 1);
    m.set({0, 0, 0}, 1);  // makes the bounding box 65001 wide: 4064^2 chunk table entries
    auto h = this->trace(m, this->make({64000.5f, 3.5f, 65000.5f}, {1, 0, 0}));
    ASSERT_TRUE(h.is_hit());
    EXPECT_EQ(h.voxel, glm::ivec3(65000, 3, 65000));
    EXPECT_EQ(h.normal, face::neg_x);
    EXPECT_FLOAT_EQ(h.t, 1000.0f - 0.5f);
}

TYPED_TEST(edge_cases, empty_model_misses) {
    voxel_model m;
    EXPECT_FALSE(this->trace(m, this->make({0, 0, 0}, {1, 1, 1})).is_hit());
}

TEST(dense_grid, rejects_a_chunk_table_over_the_limit) {
    voxel_model m;
    m.set({0, 0, 0}, 1);
    m.set({(1 << 20) - 1, (1 << 20) - 1, 4000}, 1);
    EXPECT_THROW(dense_grid{m}, voxray::error);
}

}  // namespace
