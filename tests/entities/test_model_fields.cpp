// Entity models' brick distance fields on every backend: a walk that crosses empty space
// by them gives the reference's hits in far fewer steps than the walk voxel by voxel. (The
// fields themselves: test_entity_model.cpp.)
#include <gtest/gtest.h>

#include "every_backend.hpp"
#include "scene_cases.hpp"

namespace voxray {
namespace {

using namespace voxray::test;

template <class Backend>
struct model_fields_on : ::testing::Test {};
TYPED_TEST_SUITE(model_fields_on, every_backend, backend_names);

// A 64^3 model empty but for its two far corners, turned and placed twice: with fields
// and without. Rays through its middle cross some 64 empty voxels; with fields every hit
// is the reference's, in a few moves.
TYPED_TEST(model_fields_on, empty_space_is_crossed_in_a_few_moves) {
    voxel_model corners;
    corners.set({0, 0, 0}, 3);
    corners.set({63, 63, 63}, 4);
    voxel_model world_model = single_voxel({0, -500, 0});
    dense_grid world(world_model);
    std::uint64_t steps[2] = {0, 0};
    for (model_fields fields : {model_fields::bricks, model_fields::none}) {
        scene<dense_grid> s(world);
        model_id m = s.add_model(corners, fields);
        s.add(m, {glm::vec3(0.0f), glm::angleAxis(0.3f, glm::normalize(glm::vec3(1, 2, 3)))});
        std::vector<ray> rays;
        rng g(4);
        for (int i = 0; i < 200; ++i) {  // from far off, through the model's middle and its corners
            ray r;
            r.origin = glm::vec3(g.uniform(-200, 200), g.uniform(-200, 200), 200.0f);
            glm::vec3 target = i % 4 == 0 ? glm::vec3(g.uniform(-40, 40), g.uniform(-40, 40), g.uniform(-40, 40))
                                          : glm::vec3(g.uniform(-8, 8), g.uniform(-8, 8), g.uniform(-8, 8));
            r.direction = glm::normalize(target - r.origin);
            rays.push_back(r);
        }
        scene_reference ref(world_model, s);
        tracer<TypeParam, scene<dense_grid>> t(s);
        auto c = check_against(t, ref, rays);
        EXPECT_EQ(c.mismatches, 0u) << c.first;
        std::vector<hit> hits(rays.size());
        t.closest_hit(rays, hits);
        for (auto& h : hits) steps[fields == model_fields::none] += h.steps;
    }
    // Voxel by voxel each ray takes some 64 steps in the model; by the fields a handful.
    EXPECT_GT(steps[1], 40u * 200u);
    EXPECT_LT(steps[0] * 4u, steps[1]) << "fields " << steps[0] << " steps, voxel by voxel " << steps[1];
}

}  // namespace
}  // namespace voxray
