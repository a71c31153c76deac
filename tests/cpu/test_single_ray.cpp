// The Embree-like conveniences of tracer: one ray at a time (closest_hit(ray), occluded(ray))
// and occlusion flags for a batch. Each must give exactly what the batch calls give.
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "every_backend.hpp"
#include "hit_bits.hpp"
#include "random_models.hpp"
#include "voxray/brickmap/brickmap.hpp"
#include "voxray/check/ray_sets.hpp"
#include "voxray/dense_grid/dense_grid.hpp"

using namespace voxray;

namespace {

template <class Backend, class Structure>
void single_rays_match_batches(const Structure& s, const box3i& bounds) {
    tracer<Backend, Structure> t(s);
    // More than one occlusion chunk (4096), so the chunking is exercised.
    auto rays = random_rays(bounds, 5000, 41);
    std::vector<hit> closest(rays.size()), any(rays.size());
    t.closest_hit(rays, closest);
    t.any_hit(rays, any);
    std::vector<std::uint8_t> flags(rays.size(), 7);
    t.occluded(rays, flags);
    std::size_t hits = 0, bad_closest = 0, bad_flag = 0, bad_single_flag = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        hits += closest[i].is_hit();
        bad_closest += !test::same_bits(t.closest_hit(rays[i]), closest[i]);
        bad_flag += flags[i] != (any[i].is_hit() ? 1 : 0);
        bad_single_flag += t.occluded(rays[i]) != any[i].is_hit();
    }
    EXPECT_GT(hits, rays.size() / 10) << "too few hits to test anything";
    EXPECT_EQ(bad_closest, 0u) << Backend::name << ": closest_hit(ray) differs from the batch";
    EXPECT_EQ(bad_flag, 0u) << Backend::name << ": occluded flags differ from any_hit";
    EXPECT_EQ(bad_single_flag, 0u) << Backend::name << ": occluded(ray) differs from any_hit";
}

template <class Backend>
struct SingleRayOn : ::testing::Test {};
TYPED_TEST_SUITE(SingleRayOn, test::every_backend, test::backend_names);

TYPED_TEST(SingleRayOn, MatchesBatches) {
    voxel_model model = test::random_model(24, 0.05f, 9, {-5, 3, -7});
    single_rays_match_batches<TypeParam>(dense_grid(model), model.bounds());
    single_rays_match_batches<TypeParam>(brickmap<>(model), model.bounds());
}

TEST(SingleRay, TooFewFlagsIsAnError) {
    voxel_model model = test::solid_block({0, 0, 0}, {2, 2, 2});
    dense_grid grid(model);
    tracer<cpu, dense_grid> t(grid);
    std::vector<ray> rays(3);
    std::vector<std::uint8_t> flags(2);
    EXPECT_THROW(t.occluded(rays, flags), error);
}

}  // namespace
