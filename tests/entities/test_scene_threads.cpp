// Moves, adds and removes from several threads while tracers of two backends update and
// trace (candidates by the BVH, then by chunk lists), and while the world itself is edited
// and saved (run under ThreadSanitizer by scripts/test.sh): no race, and once the threads
// are done every backend matches the reference for the scene as it ended.
#include <gtest/gtest.h>

#include <thread>

#include "scene_cases.hpp"
#include "temp_dir.hpp"
#include "voxray/naadf/serialize.hpp"
#include "voxray/cpu.hpp"

namespace voxray {
namespace {

using namespace voxray::test;

TEST(scene_threads, moves_from_several_threads_while_tracers_update) {
    voxel_model world_model = test_world();
    naadf world(world_model);
    scene<naadf> s(world);
    for (auto& m : test_models()) s.add_model(m);
    box3i b = world_model.bounds();
    auto ids = place_random(s, 3, b, 300, 4);
    tracer<cpu, scene<naadf>> simd(s);
    tracer<cpu_scalar, scene<naadf>> scalar(s, cpu_options{1});
    std::vector<std::thread> movers;
    for (int k = 0; k < 3; ++k)
        movers.emplace_back([&, k] {
            rng g(100 + k);
            for (int round = 0; round < 40; ++round) {
                for (std::size_t i = k; i < ids.size(); i += 3) {
                    pose p = s.instance(ids[i])->where;
                    p.position += glm::vec3(g.uniform(-2, 2), g.uniform(-2, 2), g.uniform(-2, 2));
                    p.rotation = test_rotation(g, round);
                    s.move(ids[i], p);
                }
                if (k == 0) {  // one thread also adds and removes its own instances
                    instance_id extra = s.add(1, {glm::vec3(b.min + b.max) * 0.5f});
                    s.remove(extra);
                }
            }
        });
    auto edit = [&](auto& target) {
        for (int i = 0; i < 20; ++i) target.set(b.min + glm::ivec3(i, 0, 0), std::uint8_t(i % 2 ? 0 : 3));
    };
    std::thread editor([&] { edit(world); });
    temp_dir dir;
    std::thread saver([&] {  // the world saved while it is edited and scenes over it update
        for (int i = 0; i < 3; ++i) save(world, dir.path / ("world_" + std::to_string(i) + ".vxna"));
    });
    auto rays = scene_rays(s, b, 500, 8);
    std::vector<hit> hits(rays.size());
    for (int frame = 0; frame < 20; ++frame) {
        // Halfway, candidates by chunk lists (rebuilt at each commit from then on).
        if (frame == 10) s.set_candidates(entity_candidates::chunk_lists);
        simd.update(s);
        simd.closest_hit(rays, hits);
        scalar.update(s);
        scalar.closest_hit(rays, hits);
    }
    for (auto& m : movers) m.join();
    editor.join();
    saver.join();
    EXPECT_TRUE(std::filesystem::exists(dir.path / "world_2.vxna"));
    simd.update(s);
    scalar.update(s);
    edit(world_model);
    scene_reference ref(world_model, s);
    EXPECT_EQ(check_against(simd, ref, rays).mismatches, 0u);
    EXPECT_EQ(check_against(scalar, ref, rays).mismatches, 0u);
}

}  // namespace
}  // namespace voxray
