// Entity models cut from a structure (entities/region_model.hpp): the voxels are the
// structure's, and an instance put back where the region was cut is hit exactly where the
// structure is, on every backend.
#include <gtest/gtest.h>

#include "error_of.hpp"
#include "every_backend.hpp"
#include "scene_cases.hpp"
#include "voxray/dense_grid/read_box.hpp"
#include "voxray/entities/region_model.hpp"
#include "voxray/naadf/read_box.hpp"

namespace voxray {
namespace {

using namespace voxray::test;

// A box of the test world holding solid voxels and empty space, and not aligned to chunks.
box3i cut_box(const voxel_model& world) {
    box3i b = world.bounds();
    glm::ivec3 lo = b.min + b.extent() / 4 + 3, hi = lo + glm::min(b.extent() / 2, glm::ivec3(45));
    return box3i{lo, hi};
}

TEST(region_model, holds_the_structures_voxels) {
    voxel_model world_model = test_world();
    box3i box = cut_box(world_model);
    dense_grid dense(world_model);
    naadf nested(world_model);
    voxel_model from_dense = region_model(dense, box), from_naadf = region_model(nested, box);
    std::size_t solid = 0;
    for (int z = box.min.z - 1; z <= box.max.z; ++z)
        for (int y = box.min.y - 1; y <= box.max.y; ++y)
            for (int x = box.min.x - 1; x <= box.max.x; ++x) {
                glm::ivec3 p(x, y, z);
                std::uint8_t want = box.contains(p) ? world_model.get(p) : 0;
                ASSERT_EQ(from_dense.get(p), want) << x << " " << y << " " << z;
                ASSERT_EQ(from_naadf.get(p), want) << x << " " << y << " " << z;
                solid += want != 0;
            }
    EXPECT_GT(solid, 100u);
    EXPECT_LT(solid, std::size_t(box.volume()));
}

TEST(region_model, refuses_regions_beyond_the_model_limits) {
    voxel_model m = single_voxel({0, 0, 0});
    EXPECT_THROW(region_model(m, box3i{{0, 0, 0}, {0, 4, 4}}), error);
    auto what = error_of([&] { region_model(m, box3i{{0, 0, 0}, {2000, 4, 4}}); });
    EXPECT_NE(what.find("2000 x 4 x 4 voxels; each edge must lie in 1..1024"), std::string::npos) << what;
}

template <class Backend>
struct region_model_on : ::testing::Test {};
TYPED_TEST_SUITE(region_model_on, every_backend, backend_names);

// The region as an instance over an empty world, at the centre of its bounds with no
// rotation: exact against the reference, and where the structure is: the hits name the
// voxels and faces (or misses) that the world's voxels in the box give. (The instance's
// frame adds P and subtracts it again, so t agrees to rounding, and a ray grazing a
// voxel's edge may meet its neighbour: a few in a thousand at most.)
TYPED_TEST(region_model_on, an_instance_put_back_is_hit_where_the_structure_is) {
    voxel_model world_model = test_world();
    box3i box = cut_box(world_model);
    naadf nested(world_model);
    voxel_model region = region_model(nested, box);
    box3i b = region.bounds();
    voxel_model far_voxel = single_voxel({0, -5000, 0});
    dense_grid far_world(far_voxel);
    scene<dense_grid> s(far_world);
    model_id m = s.add_model(region);
    s.add(m, {glm::vec3(b.min + b.max) * 0.5f});
    voxel_model cropped;  // the world's voxels in the box, read one by one
    for (int z = box.min.z; z < box.max.z; ++z)
        for (int y = box.min.y; y < box.max.y; ++y)
            for (int x = box.min.x; x < box.max.x; ++x)
                if (std::uint8_t v = world_model.get({x, y, z})) cropped.set({x, y, z}, v);
    dense_grid alone(cropped);
    tracer<TypeParam, scene<dense_grid>> t(s);
    tracer<TypeParam, dense_grid> alone_tracer(alone);
    auto rays = check_rays(b, 2, 1000, 8);
    scene_reference ref(far_voxel, s);
    auto c = check_against(t, ref, rays);
    EXPECT_EQ(c.mismatches, 0u) << c.first;
    std::vector<hit> got(rays.size()), want(rays.size());
    t.closest_hit(rays, got);
    alone_tracer.closest_hit(rays, want);
    std::size_t hits = 0, elsewhere = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        hit g = got[i], w = want[i];
        hits += w.status == VX_STATUS_HIT;
        if (g.status != w.status) ++elsewhere;
        if (g.status != VX_STATUS_HIT || w.status != VX_STATUS_HIT) continue;
        ASSERT_EQ(hit_instance(g), std::optional<std::uint32_t>(0u));
        ASSERT_EQ(hit_palette_index(g), w.material);
        if (g.voxel != w.voxel || g.normal != w.normal) ++elsewhere;
        else EXPECT_NEAR(g.t, w.t, 1e-4f * std::max(1.0f, w.t)) << describe(rays[i]);
    }
    EXPECT_GT(hits, 100u);
    EXPECT_LE(elsewhere * 200u, hits) << elsewhere << " of " << hits << " hits elsewhere";
}

}  // namespace
}  // namespace voxray
