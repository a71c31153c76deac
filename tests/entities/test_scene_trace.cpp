// Scenes against the brute-force reference on every backend: 1 to 10,000 instances over
// every world kind (rotations of every kind, scales, overlaps, instances partly
// outside the world), candidates found by the BVH and by chunk lists; the backends agree
// with the scalar CPU bit for bit, steps included; 100 frames of motion stay exact; a
// frame sends only what moved.
#include <gtest/gtest.h>

#include "every_backend.hpp"
#include "scene_cases.hpp"

namespace voxray {
namespace {

using namespace voxray::test;

template <class Backend>
struct scene_on : ::testing::Test {};
TYPED_TEST_SUITE(scene_on, every_backend, backend_names);

// The scene over `world`, against the reference and (all hit fields) the scalar CPU. The
// instances and rays depend on the seed alone, so every world kind shares the reference's
// hits `want` (traced by the first).
template <class Backend, class World>
void check_scene(World& world, const voxel_model& world_model, int count, std::size_t ray_count, std::uint64_t seed,
                 std::vector<hit>& want, entity_candidates how) {
    scene<World> s(world);
    s.set_candidates(how);
    auto models = test_models();
    for (auto& m : models) s.add_model(m);
    place_random(s, std::uint32_t(models.size()), world_model.bounds(), count, seed);
    auto rays = scene_rays(s, world_model.bounds(), ray_count, seed);
    if (want.empty()) {
        scene_reference ref(world_model, s);
        want = reference_hits(ref, rays);
    }
    ASSERT_EQ(want.size(), rays.size());
    tracer<Backend, scene<World>> t(s);
    auto c = check_against(t, std::span<const hit>(want), rays);
    EXPECT_EQ(c.mismatches, 0u) << Backend::name << ", " << World::name << ", " << candidates_name(how) << ", "
                                << count << " instances, " << c.rays << " rays; first:\n" << c.first;
    EXPECT_GT(c.entity_hits, rays.size() / 50) << "too few rays hit an instance to test anything";

    std::vector<hit> got(rays.size()), scalar(rays.size());
    t.closest_hit(rays, got);
    tracer<cpu_scalar, scene<World>>(s, cpu_options{1}).closest_hit(rays, scalar);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) differ += same_bits(got[i], scalar[i]) ? 0 : 1;
    EXPECT_EQ(differ, 0u) << Backend::name << ", " << World::name << ", " << candidates_name(how)
                          << ": differs from cpu-scalar (steps included)";
}

// Every registered world kind (registered::scene_worlds) under the same instances and rays,
// candidates by the BVH; then by chunk lists over NAADF (how candidates are found does not
// depend on the world kind).
TYPED_TEST(scene_on, matches_the_reference_from_1_to_10000_instances) {
    voxel_model world_model = test_world();
    for (std::pair<int, int> c : {std::pair{1, 3000}, std::pair{100, 3000}, std::pair{10000, 400}}) {
        std::vector<hit> want;  // (a pair, not a structured binding: clang 14 cannot capture those)
        auto seed = 7 + std::uint64_t(c.first);
        for_each_type(registered::scene_worlds{}, [&]<class World>() {
            World world(world_model);
            check_scene<TypeParam>(world, world_model, c.first, std::size_t(c.second), seed, want, entity_candidates::bvh);
        });
        naadf world(world_model);
        check_scene<TypeParam>(world, world_model, c.first, std::size_t(c.second), seed, want, entity_candidates::chunk_lists);
    }
}

// 100 frames: every instance moves (a straight line across the world, and a spin), the
// tracer takes the changes, and every frame matches the reference.
template <class Backend>
void check_motion(entity_candidates how) {
    voxel_model world_model = test_world();
    naadf world(world_model);
    scene<naadf> s(world);
    s.set_candidates(how);
    auto models = test_models();
    for (auto& m : models) s.add_model(m);
    box3i b = world_model.bounds();
    auto ids = place_random(s, std::uint32_t(models.size()), b, 60, 99);
    tracer<Backend, scene<naadf>> t(s);
    glm::vec3 step = glm::vec3(b.extent()) / 60.0f;
    std::size_t mismatches = 0, entity_hits = 0;
    std::string first;
    for (int frame = 1; frame <= 100; ++frame) {
        std::vector<std::pair<instance_id, pose>> moves;
        for (std::size_t i = 0; i < ids.size(); ++i) {
            pose p = s.instance(ids[i])->where;
            p.position += step * glm::vec3(i % 2 ? 1.0f : -0.5f, 0.25f, i % 3 ? 0.5f : -1.0f);
            p.rotation = glm::angleAxis(0.05f * float(i % 7), glm::normalize(glm::vec3(1, 2, 3))) * p.rotation;
            moves.push_back({ids[i], p});
        }
        s.move(moves);
        t.update(s);
        scene_reference ref(world_model, s);
        auto rays = scene_rays(s, b, 300, 1000 + frame);
        auto c = check_against(t, ref, rays);
        if (c.mismatches > 0 && first.empty()) first = "frame " + std::to_string(frame) + ": " + c.first;
        mismatches += c.mismatches;
        entity_hits += c.entity_hits;
    }
    EXPECT_EQ(mismatches, 0u) << Backend::name << ", " << candidates_name(how) << "; first:\n" << first;
    EXPECT_GT(entity_hits, 1000u);
}

TYPED_TEST(scene_on, stays_exact_over_100_frames_of_motion) {
    for (entity_candidates how : every_entity_candidates) check_motion<TypeParam>(how);
}

// Moving 3 of 2,000 instances sends their records and the BVH nodes above them, not the
// scene: at most 3 x (16 + 8 x 32 levels) words. With chunk lists, also the words of the
// chunks whose lists changed and the lists new to the frame (the others stay where they
// are): a small part of the lists' words.
TYPED_TEST(scene_on, a_frame_sends_what_moved) {
    for (entity_candidates how : every_entity_candidates) {
        voxel_model world_model = test_world();
        naadf world(world_model);
        scene<naadf> s(world);
        s.set_candidates(how);
        for (auto& m : test_models()) s.add_model(m);
        auto ids = place_random(s, 3, world_model.bounds(), 2000, 5);
        tracer<TypeParam, scene<naadf>> t(s);
        for (int i = 0; i < 3; ++i) {
            pose p = s.instance(ids[i * 100])->where;
            p.position.x += 7.0f;
            s.move(ids[i * 100], p);
        }
        t.update(s);
        std::uint64_t most = 3 * (VX_SC_INSTANCE_WORDS + VX_SC_NODE_WORDS * VX_SC_MAX_DEPTH) * 4;
        auto blob = s.blob();
        if (std::uint32_t lists = blob[VX_SC_HEADER_CHUNKS]; lists != 0) most += (blob.size() - lists) * 4 / 32;
        EXPECT_GT(t.bytes_uploaded_last_update(), 0u);
        EXPECT_LE(t.bytes_uploaded_last_update(), most) << candidates_name(how) << ", scene of " << s.bytes() << " bytes";
        scene_reference ref(world_model, s);
        auto rays = scene_rays(s, world_model.bounds(), 1000, 3);
        EXPECT_EQ(check_against(t, ref, rays).mismatches, 0u) << candidates_name(how);
    }
}

}  // namespace
}  // namespace voxray
