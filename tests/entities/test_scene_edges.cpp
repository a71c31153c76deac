// Extreme scenes on every backend, candidates found by the BVH and by chunk lists (1,000
// instances stacked in one chunk, a ray grazing hundreds of boxes, instances added and
// removed between frames), and bad input: clear errors naming the value, never a wrong
// answer.
#include <gtest/gtest.h>

#include <limits>

#include "error_of.hpp"
#include "every_backend.hpp"
#include "scene_cases.hpp"

namespace voxray {
namespace {

using namespace voxray::test;

template <class Backend>
struct scene_extremes_on : ::testing::Test {};
TYPED_TEST_SUITE(scene_extremes_on, every_backend, backend_names);

TYPED_TEST(scene_extremes_on, a_thousand_instances_stacked_in_one_chunk) {
    for (entity_candidates how : every_entity_candidates) {
        voxel_model world_model = test_world();
        dense_grid world(world_model);
        scene<dense_grid> s(world);
        s.set_candidates(how);
        for (auto& m : test_models()) s.add_model(m);
        rng g(3);
        glm::vec3 at = glm::vec3(world_model.bounds().min + world_model.bounds().max) * 0.5f;
        for (int i = 0; i < 1000; ++i)
            s.add(model_id(g.below(2)), {at + glm::vec3(g.uniform(0, 16), g.uniform(0, 16), g.uniform(0, 16)), test_rotation(g, i)});
        scene_reference ref(world_model, s);
        tracer<TypeParam, scene<dense_grid>> t(s);
        auto rays = scene_rays(s, world_model.bounds(), 2000, 11);
        auto c = check_against(t, ref, rays);
        EXPECT_EQ(c.mismatches, 0u) << candidates_name(how) << ": " << c.first;
        EXPECT_GT(c.entity_hits, 200u);
    }
}

// 300 instances in a row along x, rays along the row just above, on and below their tops:
// each ray passes hundreds of boxes, and nothing caps how many it opens.
TYPED_TEST(scene_extremes_on, rays_grazing_hundreds_of_boxes) {
    for (entity_candidates how : every_entity_candidates) {
        voxel_model world_model = single_voxel({0, -50, 0});
        dense_grid world(world_model);
        scene<dense_grid> s(world);
        s.set_candidates(how);
        model_id cube = s.add_model(solid_block({0, 0, 0}, {4, 4, 4}, 5));
        for (int i = 0; i < 300; ++i) s.add(cube, {glm::vec3(6.0f * float(i), 0.0f, 0.0f)});
        std::vector<ray> rays;
        for (float y : {1.999f, 2.0f, 2.001f, -2.0f, 0.0f})
            for (float z : {-1.5f, 0.0f, 1.999f, 2.0f}) {
                ray r;
                r.origin = {-20.0f, y, z};
                r.direction = glm::normalize(glm::vec3(1.0f, 1e-6f * z, 0.0f));
                rays.push_back(r);
                r.origin = {2000.0f, y, z};
                r.direction = {-1.0f, 0.0f, 0.0f};
                rays.push_back(r);
            }
        scene_reference ref(world_model, s);
        tracer<TypeParam, scene<dense_grid>> t(s);
        auto c = check_against(t, ref, rays);
        EXPECT_EQ(c.mismatches, 0u) << candidates_name(how) << ": " << c.first;
        // A ray just above the row, inside every padded box, opens all of the tree's 149 nodes
        // (75 leaves of 4), or walks all 113 chunks along the row: its steps say so.
        ray above;
        above.origin = {-20.0f, 2.0f + 1e-4f, 0.0f};
        above.direction = {1.0f, 0.0f, 0.0f};
        std::vector<hit> h(1);
        t.closest_hit(std::span<const ray>(&above, 1), h);
        EXPECT_FALSE(h[0].is_hit());
        EXPECT_GE(h[0].steps, how == entity_candidates::bvh ? 149u : 113u) << candidates_name(how);
    }
}

TYPED_TEST(scene_extremes_on, instances_come_and_go_between_frames) {
    for (entity_candidates how : every_entity_candidates) {
        voxel_model world_model = test_world();
        naadf world(world_model);
        scene<naadf> s(world);
        s.set_candidates(how);
        for (auto& m : test_models()) s.add_model(m);
        auto ids = place_random(s, 3, world_model.bounds(), 200, 21);
        tracer<TypeParam, scene<naadf>> t(s);
        for (int frame = 0; frame < 6; ++frame) {
            for (std::size_t i = frame; i < ids.size(); i += 5) s.remove(ids[i]);
            ids.erase(std::remove_if(ids.begin(), ids.end(), [&](instance_id id) { return !s.instance(id); }), ids.end());
            auto more = place_random(s, 3, world_model.bounds(), 40 + 30 * frame, 50 + frame);  // reuses free slots
            ids.insert(ids.end(), more.begin(), more.end());
            t.update(s);
            scene_reference ref(world_model, s);
            auto c = check_against(t, ref, scene_rays(s, world_model.bounds(), 600, 70 + frame));
            EXPECT_EQ(c.mismatches, 0u) << candidates_name(how) << ", frame " << frame << ": " << c.first;
        }
    }
}

// Two instances in the very same place tie everywhere: the lower slot wins, on every
// backend, whatever order the BVH visits them in.
TYPED_TEST(scene_extremes_on, identical_instances_tie_to_the_lower_slot) {
    for (entity_candidates how : every_entity_candidates) {
        voxel_model world_model = single_voxel({0, -50, 0});
        dense_grid world(world_model);
        scene<dense_grid> s(world);
        s.set_candidates(how);
        model_id m = s.add_model(random_model(10, 0.4f, 3));
        pose p{glm::vec3(3.5f, 1.0f, -2.0f), glm::quat(0.9f, 0.1f, 0.3f, -0.2f)};
        for (int i = 0; i < 40; ++i) s.add(m, p);
        scene_reference ref(world_model, s);
        tracer<TypeParam, scene<dense_grid>> t(s);
        auto rays = scene_rays(s, world_model.bounds(), 800, 5);
        auto c = check_against(t, ref, rays);
        EXPECT_EQ(c.mismatches, 0u) << candidates_name(how) << ": " << c.first;
        std::vector<hit> hits(rays.size());
        t.closest_hit(rays, hits);
        std::size_t on_slot_0 = 0;
        for (auto& h : hits) on_slot_0 += hit_instance(h) == 0u ? 1 : 0;
        EXPECT_GT(on_slot_0, 100u) << candidates_name(how);
        for (auto& h : hits) EXPECT_TRUE(!hit_instance(h) || *hit_instance(h) == 0u);
    }
}

TEST(scene_input, bad_poses_are_refused_naming_the_value) {
    dense_grid world(single_voxel({0, 0, 0}));
    scene<dense_grid> s(world);
    model_id m = s.add_model(single_voxel({0, 0, 0}));
    float nan = std::numeric_limits<float>::quiet_NaN();
    EXPECT_NE(error_of([&] { s.add(m, {glm::vec3(0), glm::quat(0, 0, 0, 0)}); }).find("cannot be normalised"), std::string::npos);
    EXPECT_NE(error_of([&] { s.add(m, {glm::vec3(0), glm::quat(nan, 0, 0, 1)}); }).find("rotation (w nan"), std::string::npos);
    EXPECT_NE(error_of([&] { s.add(m, {glm::vec3(0), glm::quat(1, 0, 0, 0), 0.0f}); }).find("scale 0 "), std::string::npos);
    EXPECT_NE(error_of([&] { s.add(m, {glm::vec3(0), glm::quat(1, 0, 0, 0), nan}); }).find("scale nan"), std::string::npos);
    EXPECT_NE(error_of([&] { s.add(m, {glm::vec3(nan, 0, 0)}); }).find("position (nan"), std::string::npos);
    instance_id id = s.add(m, {});
    EXPECT_NE(error_of([&] { s.move(id, {glm::vec3(0), glm::quat(0, 0, 0, 0)}); }).find("rotation"), std::string::npos);
    // A failed batch moves nothing.
    std::vector<std::pair<instance_id, pose>> batch{{id, {glm::vec3(5, 0, 0)}}, {id + 7, {}}};
    EXPECT_NE(error_of([&] { s.move(batch); }).find("instance " + std::to_string(id + 7) + " does not exist"), std::string::npos);
    EXPECT_EQ(s.instance(id)->where.position, glm::vec3(0));
    EXPECT_EQ(s.instance_count(), 1u);
}

TEST(scene_input, removed_models_and_instances_are_refused) {
    dense_grid world(single_voxel({0, 0, 0}));
    scene<dense_grid> s(world);
    model_id a = s.add_model(single_voxel({0, 0, 0}));
    model_id b = s.add_model(solid_block({0, 0, 0}, {2, 2, 2}));
    instance_id id = s.add(a, {});
    EXPECT_NE(error_of([&] { s.remove_model(a); }).find("model 0 still has 1 instances"), std::string::npos);
    s.remove_model(b);
    EXPECT_NE(error_of([&] { s.add(b, {}); }).find("model 1 was removed"), std::string::npos);
    EXPECT_NE(error_of([&] { s.add(9, {}); }).find("model 9 does not exist"), std::string::npos);
    s.remove(id);
    EXPECT_NE(error_of([&] { s.move(id, {}); }).find("instance 0 was removed"), std::string::npos);
    EXPECT_NE(error_of([&] { s.remove(id); }).find("instance 0 was removed"), std::string::npos);
    // The scene still traces: nothing but the world.
    tracer<cpu, scene<dense_grid>> t(s);
    ray r;
    r.origin = {0.5f, 0.5f, -5.0f};
    EXPECT_TRUE(t.closest_hit(r).is_hit());
    EXPECT_FALSE(hit_instance(t.closest_hit(r)));
}

// Instances spread too wide for a grid of chunks: the chunk lists refuse them naming the
// span and the limit, and the scene still serves them by the BVH.
TEST(scene_input, chunk_lists_refuse_instances_spread_too_wide) {
    dense_grid world(single_voxel({0, 0, 0}));
    scene<dense_grid> s(world);
    model_id m = s.add_model(solid_block({0, 0, 0}, {2, 2, 2}));
    s.add(m, {glm::vec3(0.0f)});
    s.add(m, {glm::vec3(1e6f, 1e6f, 1e6f)});
    s.set_candidates(entity_candidates::chunk_lists);
    EXPECT_NE(error_of([&] { s.blob(); }).find("the instances span 62502 x 62502 x 62502 chunks of 16^3 voxels, above "
                                               "the limit of 16777216 chunks"),
              std::string::npos);
    s.set_candidates(entity_candidates::bvh);
    tracer<cpu, scene<dense_grid>> t(s);
    ray r;
    r.origin = {0.5f, 0.5f, -5.0f};
    EXPECT_TRUE(hit_instance(t.closest_hit(r)));
}

TEST(scene_input, models_beyond_the_edge_limit_are_refused) {
    voxel_model wide;
    wide.set({0, 0, 0}, 1);
    wide.set({VX_EM_MAX_EDGE, 0, 0}, 1);
    EXPECT_NE(error_of([&] { entity_model m(wide); }).find("1025 x 1 x 1 voxels, above the limit of 1024"), std::string::npos);
}

}  // namespace
}  // namespace voxray
