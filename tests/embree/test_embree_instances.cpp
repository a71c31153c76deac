// Embree's instancing peer of voxray's scenes (embree/instanced_scene.hpp) answers the same
// rays as voxray's brute-force scene reference: the same hit or miss, on the same instance or
// the world, the same voxel in that model's coordinates, t within float rounding; rays that
// start inside solid or graze an edge (where float quads and the exact walk may part) aside.
#include <gtest/gtest.h>

#include <cmath>

#include "random_models.hpp"
#include "voxray/cpu.hpp"
#include "voxray/embree/instanced_scene.hpp"
#include "voxray/entities/reference.hpp"
#include "voxray/entities/worlds/dense_grid.hpp"
#include "voxray/rays.hpp"
#include "voxray/scenes/builtin.hpp"

namespace voxray {
namespace {

using namespace voxray::test;

TEST(embree_instances, answer_as_the_scene_reference_does) {
    voxel_model world_model = scenes::make_builtin("terrain:64", 2);
    dense_grid world(world_model);
    scene<dense_grid> s(world);
    embree::instanced_scene peer(world_model);
    voxel_model models[] = {random_model(8, 0.5f, 3, {2, -4, 1}), hollow_box(12)};
    for (auto& m : models) {
        s.add_model(m);
        peer.add_model(m);
    }
    rng g(5);
    for (int i = 0; i < 60; ++i) {
        pose p{glm::vec3(g.uniform(0, 64), g.uniform(0, 64), g.uniform(20, 50)),
               glm::quat(g.uniform(-1, 1), g.uniform(-1, 1), g.uniform(-1, 1), g.uniform(-1, 1) + 0.01f), 1.0f};
        p = checked_pose(p);
        s.add(model_id(i % 2), p);
        peer.add(std::uint32_t(i % 2), p);
    }
    peer.commit();
    auto rays = primary_rays(auto_camera(world_model.bounds(), world_model.up_axis, 1), 160, 120);
    std::vector<hit> got(rays.size());
    peer.closest_hit(rays, got);
    scene_reference ref(world_model, s);
    std::size_t compared = 0, same = 0, instance_hits = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        hit want = ref.trace(rays[i], VX_MODE_CLOSEST);
        ++compared;
        instance_hits += hit_instance(want) ? 1 : 0;
        bool agree = want.is_hit() == got[i].is_hit() &&
                     (!want.is_hit() || (want.material == got[i].material && want.voxel == got[i].voxel &&
                                         std::abs(want.t - got[i].t) <= 1e-3f * std::max(1.0f, want.t)));
        same += agree ? 1 : 0;
    }
    EXPECT_GT(instance_hits, compared / 20);
    // Float quads through a float transform part from the exact walk only on edges and corners.
    EXPECT_GE(double(same), 0.995 * double(compared)) << same << " of " << compared << " agree";
}

}  // namespace
}  // namespace voxray
