// The edge-case rays with exact expectations, on every structure and backend: every
// face, starts inside solid, tmin/tmax clipping, axis-parallel and zero or negative
// components, rays along face planes and edges, corners crossed, invalid rays, far
// origins and coordinates near 65000. Every ray is also checked against the oracle in
// both modes (conformance::traced).
#pragma once
#include <cmath>

#include "fixture.hpp"
#include "random_models.hpp"
#include "special_rays.hpp"

namespace voxray::test {

template <class Case>
struct edge_cases : conformance<Case> {};
TYPED_TEST_SUITE_P(edge_cases);

inline ray make_ray(glm::vec3 o, glm::vec3 d, float tmin = 0.0f, float tmax = INFINITY) { return {o, tmin, d, tmax}; }

TYPED_TEST_P(edge_cases, hits_every_face_with_the_right_normal) {
    auto m = single_voxel({3, 4, 5}, 7);
    glm::vec3 c(3.5f, 4.5f, 5.5f);
    struct { glm::vec3 dir; face f; } cases[] = {
        {{1, 0, 0}, face::neg_x}, {{-1, 0, 0}, face::pos_x}, {{0, 1, 0}, face::neg_y},
        {{0, -1, 0}, face::pos_y}, {{0, 0, 1}, face::neg_z}, {{0, 0, -1}, face::pos_z}};
    for (auto& k : cases) {
        hit h = this->traced(m, make_ray(c - k.dir * 10.0f, k.dir));
        ASSERT_TRUE(h.is_hit());
        EXPECT_EQ(h.normal, k.f) << face_name(h.normal);
        EXPECT_EQ(h.voxel, glm::ivec3(3, 4, 5));
        EXPECT_EQ(h.material, 7u);
        EXPECT_FLOAT_EQ(h.t, 9.5f);
    }
}

TYPED_TEST_P(edge_cases, start_inside_solid_hits_at_tmin) {
    auto m = single_voxel({0, 0, 0});
    std::vector<ray> rays{make_ray({0.25f, 0.5f, 0.75f}, {1, 1, 0}, 0.1f), make_ray({0.5f, 0.5f, 0.5f}, {0, 0, -1})};
    auto hits = this->traced(m, rays);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        ASSERT_TRUE(hits[i].is_hit()) << i;
        EXPECT_EQ(hits[i].normal, face::inside) << i;
        EXPECT_EQ(hits[i].voxel, glm::ivec3(0));
        EXPECT_FLOAT_EQ(hits[i].t, rays[i].tmin);
    }
}

TYPED_TEST_P(edge_cases, clipped_by_tmin_and_tmax) {
    voxel_model m;
    m.set({2, 0, 0}, 1);
    m.set({6, 0, 0}, 2);
    std::vector<ray> rays(4, make_ray({0.0f, 0.5f, 0.5f}, {1, 0, 0}));
    rays[1].tmin = 3.0f;                      // skips the first voxel
    rays[2].tmin = 3.0f, rays[2].tmax = 5.5f;  // ends before the second
    rays[3].tmin = 3.0f, rays[3].tmax = 6.0f;  // touches its face exactly
    auto hits = this->traced(m, rays);
    EXPECT_EQ(hits[0].voxel.x, 2);
    EXPECT_EQ(hits[1].voxel.x, 6);
    EXPECT_FALSE(hits[2].is_hit());
    EXPECT_TRUE(hits[3].is_hit());
    EXPECT_FLOAT_EQ(hits[3].t, 6.0f);
}

TYPED_TEST_P(edge_cases, negative_and_zero_components) {
    voxel_model m;
    m.set({-5, -6, -7}, 3);
    auto hits = this->traced(m, std::vector<ray>{make_ray({-4.5f, 10.0f, -6.5f}, {0, -2, 0}),
                                                 make_ray({-3.5f, 10.0f, -6.5f}, {0, -1, 0})});
    ASSERT_TRUE(hits[0].is_hit());
    EXPECT_EQ(hits[0].voxel, glm::ivec3(-5, -6, -7));
    EXPECT_EQ(hits[0].normal, face::pos_y);
    EXPECT_FLOAT_EQ(hits[0].t, (10.0f - -5.0f) / 2.0f);
    // Parallel to an axis, outside the voxel's slab: a miss.
    EXPECT_FALSE(hits[1].is_hit());
}

// Cells are half-open: a ray in the plane x = 0 runs inside voxel 0's slab, one in
// x = 1 (its +x face) never enters it; the same along edges.
TYPED_TEST_P(edge_cases, rays_along_face_planes_and_edges) {
    auto m = single_voxel({0, 0, 0});
    std::vector<ray> rays{make_ray({1.0f, -3.0f, 0.5f}, {0, 1, 0}), make_ray({0.0f, -3.0f, 0.5f}, {0, 1, 0}),
                          make_ray({0.5f, 4.0f, 1.0f}, {0, -1, 0}), make_ray({0.5f, 4.0f, 0.0f}, {0, -1, 0}),
                          make_ray({0.0f, -3.0f, 0.0f}, {0, 1, 0}), make_ray({1.0f, -3.0f, 0.0f}, {0, 1, 0}),
                          make_ray({0.0f, -3.0f, 1.0f}, {0, 1, 0}), make_ray({1.0f, 3.0f, 1.0f}, {0, -1, 0})};
    bool expected[] = {false, true, false, true, true, false, false, false};
    auto hits = this->traced(m, rays);
    for (std::size_t i = 0; i < rays.size(); ++i) EXPECT_EQ(hits[i].is_hit(), expected[i]) << describe(rays[i]);
    EXPECT_FLOAT_EQ(hits[1].t, 3.0f);
    EXPECT_EQ(hits[1].normal, face::neg_y);
}

// Through an edge, all tied axes step at once: voxels only touched are not hit.
TYPED_TEST_P(edge_cases, crossing_an_edge_skips_voxels_it_only_touches) {
    voxel_model m;
    m.set({1, 0, 0}, 3);
    m.set({0, 1, 0}, 4);
    m.set({2, 2, 0}, 5);
    hit h = this->traced(m, make_ray({0.5f, 0.5f, 0.5f}, {1, 1, 0}));
    ASSERT_TRUE(h.is_hit());
    EXPECT_EQ(h.voxel, glm::ivec3(2, 2, 0));
    EXPECT_EQ(h.material, 5u);
    EXPECT_FLOAT_EQ(h.t, 1.5f);
    // ...and through a corner, from outside the world.
    voxel_model c;
    c.set({1, 0, 0}, 9);  // touched at corner (1, 1, 1) only
    c.set({0, 1, 1}, 8);  // likewise
    c.set({1, 1, 1}, 2);
    hit k = this->traced(c, make_ray({-1.0f, -1.0f, -1.0f}, {1, 1, 1}));
    ASSERT_TRUE(k.is_hit());
    EXPECT_EQ(k.voxel, glm::ivec3(1, 1, 1));
    EXPECT_EQ(k.material, 2u);
    EXPECT_FLOAT_EQ(k.t, 2.0f);
}

TYPED_TEST_P(edge_cases, invalid_rays_miss) {
    auto m = solid_block({0, 0, 0}, {8, 8, 8});
    auto rays = invalid_rays({-5.0f, 4.5f, 4.5f}, {-4.0f, 4.5f, 4.5f});
    auto hits = this->traced(m, rays);
    ASSERT_TRUE(hits[0].is_hit());  // the valid ray they were all made from
    EXPECT_EQ(hits[0].voxel, glm::ivec3(0, 4, 4));
    EXPECT_EQ(hits[0].normal, face::neg_x);
    EXPECT_FLOAT_EQ(hits[0].t, 5.0f);
    for (std::size_t i = 1; i < rays.size(); ++i) {
        EXPECT_EQ(hits[i].status, VX_STATUS_MISS) << describe(rays[i]);
        EXPECT_EQ(hits[i].normal, face::none) << describe(rays[i]);
        EXPECT_EQ(hits[i].material, 0u) << describe(rays[i]);
        EXPECT_TRUE(std::isinf(hits[i].t) && hits[i].t > 0) << describe(rays[i]) << " t=" << hits[i].t;
    }
}

TYPED_TEST_P(edge_cases, far_away_origin_and_infinite_tmax) {
    auto m = single_voxel({100, 100, 100});
    hit h = this->traced(m, make_ray({100.5f, 100.5f, -60000.0f}, {0, 0, 1}));
    ASSERT_TRUE(h.is_hit());
    EXPECT_EQ(h.voxel, glm::ivec3(100, 100, 100));
    EXPECT_EQ(h.normal, face::neg_z);
    EXPECT_NEAR(h.t, 60100.0f, 0.01f);
}

// The rules for extremes (README, semantics): a ray whose crossing t overflows float
// misses (it used to hit the world's min corner at t = inf on every structure), and a
// component under VX_MIN_DIRECTION moves nothing, also over a t of 1e37 (the brickmap's
// descent used to move z by -0.19 there and hit a voxel one row down).
TYPED_TEST_P(edge_cases, overflowing_t_misses_and_tiny_components_stay_put) {
    voxel_model m;
    m.set({0, 17, 5}, 1);
    m.set({-3, 17, 5}, 2);
    m.set({22, 25, -1}, 3);
    m.set({30, 25, 0}, 4);
    typename TestFixture::structure s(m);
    typename TestFixture::tracer_type t(s);
    float threshold = 7.52316385e-37f;  // VX_MIN_DIRECTION: x moves, z does not
    std::vector<ray> rays{make_ray({1e30f, 17.5f, 5.5f}, {-1e-30f, 0, 0}),
                          make_ray({8.0f, 25.0f, 1e-30f}, {threshold, 0, -1e-38f})};
    for (mode md : {mode::closest, mode::any}) {
        auto hits = trace(t, rays, md);
        EXPECT_FALSE(hits[0].is_hit()) << mode_name(md) << ": hit " << hits[0].voxel.x << " at t = " << hits[0].t;
        ASSERT_TRUE(hits[1].is_hit()) << mode_name(md);
        EXPECT_EQ(hits[1].voxel, glm::ivec3(30, 25, 0)) << mode_name(md);
        EXPECT_TRUE(std::isfinite(hits[1].t));
    }
}

// A world 65001 voxels wide (a 4064^2 chunk table for the dense grid), at positive and
// at negative coordinates.
TYPED_TEST_P(edge_cases, coordinates_near_65000) {
    voxel_model m;
    m.set({65000, 3, 65000}, 1);
    m.set({0, 0, 0}, 2);
    std::vector<ray> rays{make_ray({64000.5f, 3.5f, 65000.5f}, {1, 0, 0}), make_ray({-10.0f, 0.5f, 0.5f}, {1, 0, 0}),
                          make_ray({65000.5f, 100.0f, 65000.5f}, {0, -1, 0})};
    auto hits = this->traced(m, rays);
    ASSERT_TRUE(hits[0].is_hit());
    EXPECT_EQ(hits[0].voxel, glm::ivec3(65000, 3, 65000));
    EXPECT_EQ(hits[0].normal, face::neg_x);
    EXPECT_FLOAT_EQ(hits[0].t, 1000.0f - 0.5f);
    EXPECT_EQ(hits[1].voxel, glm::ivec3(0, 0, 0));
    EXPECT_FLOAT_EQ(hits[1].t, 10.0f);
    EXPECT_EQ(hits[2].normal, face::pos_y);
    EXPECT_FLOAT_EQ(hits[2].t, 96.0f);

    voxel_model n;
    n.set({-65000, -3, -65000}, 4);
    n.set({-1, -1, -1}, 5);
    hit h = this->traced(n, make_ray({-64000.5f, -2.5f, -64999.5f}, {-1, 0, 0}));
    ASSERT_TRUE(h.is_hit());
    EXPECT_EQ(h.voxel, glm::ivec3(-65000, -3, -65000));
    EXPECT_EQ(h.normal, face::pos_x);
    EXPECT_FLOAT_EQ(h.t, 998.5f);
}

TYPED_TEST_P(edge_cases, empty_model_misses) {
    voxel_model m;
    auto rays = random_rays(box3i{{-4, -4, -4}, {4, 4, 4}}, 500, 3);
    rays.push_back(make_ray({0, 0, 0}, {1, 1, 1}));
    auto hits = this->traced(m, rays);
    EXPECT_EQ(count_hits(hits), 0u);
}

REGISTER_TYPED_TEST_SUITE_P(edge_cases, hits_every_face_with_the_right_normal, start_inside_solid_hits_at_tmin,
                            clipped_by_tmin_and_tmax, negative_and_zero_components, rays_along_face_planes_and_edges,
                            crossing_an_edge_skips_voxels_it_only_touches, invalid_rays_miss,
                            far_away_origin_and_infinite_tmax, overflowing_t_misses_and_tiny_components_stay_put,
                            coordinates_near_65000, empty_model_misses);

}  // namespace voxray::test
