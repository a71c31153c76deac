// The NanoVDB baseline (hdda_scene) against the reference, the dense grid traced on the
// CPU: handmade rays with known answers, then seeded random models (sparse, blocks that
// fill whole NanoVDB leaves, far from the origin) and the `voxray check` ray mix, which
// has inside starts, axis-parallel rays, corner origins and finite tmax.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "random_models.hpp"
#include "voxray/check/compare.hpp"
#include "voxray/check/ray_sets.hpp"
#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/nanovdb/hdda_scene.hpp"
#include "voxray/tracer.hpp"

namespace {

using namespace voxray;
constexpr float inf = std::numeric_limits<float>::infinity();

hit trace1(const vdb::hdda_scene& s, ray r) {
    std::vector<ray> rays{r};
    std::vector<hit> hits(1);
    s.closest_hit(rays, hits);
    return hits[0];
}

TEST(NanovdbHdda, KnownAnswers) {
    voxel_model m;
    m.set({2, 3, 4}, 7);
    m.set({40, 3, 4}, 9);  // another leaf, past empty nodes
    vdb::hdda_scene s(m);
    hit h = trace1(s, ray{{-5.5f, 3.5f, 4.5f}, 0.0f, {1, 0, 0}, inf});
    ASSERT_TRUE(h.is_hit());
    EXPECT_EQ(h.voxel, glm::ivec3(2, 3, 4));
    EXPECT_EQ(h.normal, face::neg_x);
    EXPECT_FLOAT_EQ(h.t, 7.5f);
    EXPECT_EQ(h.material, 7u);
    h = trace1(s, ray{{3.5f, 3.5f, 4.5f}, 0.0f, {1, 0, 0}, inf});
    ASSERT_TRUE(h.is_hit());
    EXPECT_EQ(h.voxel, glm::ivec3(40, 3, 4));
    EXPECT_FLOAT_EQ(h.t, 36.5f);
    EXPECT_EQ(h.material, 9u);
    h = trace1(s, ray{{2.5f, 3.5f, 4.5f}, 0.0f, {0, 1, 0}, inf});  // starts inside solid
    EXPECT_EQ(h.normal, face::inside);
    EXPECT_EQ(h.t, 0.0f);
    EXPECT_FALSE(trace1(s, ray{{-5.5f, 3.5f, 4.5f}, 0.0f, {1, 0, 0}, 7.0f}).is_hit());  // tmax before it
    EXPECT_FALSE(trace1(s, ray{{-5.5f, 3.5f, 4.5f}, 0.0f, {0, 0, 0}, inf}).is_hit());  // zero direction
    EXPECT_FALSE(trace1(s, ray{{NAN, 3.5f, 4.5f}, 0.0f, {1, 0, 0}, inf}).is_hit());
    EXPECT_FALSE(trace1(vdb::hdda_scene(voxel_model{}), ray{{0, 0, 0}, 0.0f, {1, 0, 0}, inf}).is_hit());
}

// Every ray of the check mix agrees with the reference (ties allowed, see compare.hpp).
void expect_agreement(const voxel_model& m, std::size_t count, std::uint64_t seed) {
    dense_grid grid(m);
    tracer<cpu_scalar, dense_grid> reference(grid);
    vdb::hdda_scene s(m);
    auto rays = check_rays(m.bounds(), 2, count, seed);
    std::vector<hit> expected(rays.size()), got(rays.size()), occluded(rays.size());
    reference.closest_hit(rays, expected);
    s.closest_hit(rays, got);
    s.any_hit(rays, occluded);
    agreement_counts counts;
    std::uint64_t any_mismatch = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        auto v = compare_hits(rays[i], expected[i], got[i]);
        counts.add(v);
        if (v == agreement::mismatch && counts.mismatches <= 3)
            ADD_FAILURE() << "ray " << i << " (" << rays[i].origin.x << ", " << rays[i].origin.y << ", "
                          << rays[i].origin.z << ") dir (" << rays[i].direction.x << ", " << rays[i].direction.y
                          << ", " << rays[i].direction.z << "): reference voxel (" << expected[i].voxel.x << ", "
                          << expected[i].voxel.y << ", " << expected[i].voxel.z << ") t " << expected[i].t
                          << " hit " << expected[i].is_hit() << ", nanovdb (" << got[i].voxel.x << ", "
                          << got[i].voxel.y << ", " << got[i].voxel.z << ") t " << got[i].t << " hit "
                          << got[i].is_hit();
        any_mismatch += v == agreement::same && occluded[i].is_hit() != expected[i].is_hit();
    }
    EXPECT_EQ(counts.mismatches, 0u) << counts.ties << " ties";
    EXPECT_EQ(any_mismatch, 0u);
    EXPECT_LT(counts.ties, counts.rays / 100);
}

TEST(NanovdbHdda, AgreesWithDenseGridOnSparseNoise) { expect_agreement(test::random_model(40, 0.02f, 3), 40000, 11); }
TEST(NanovdbHdda, AgreesWithDenseGridOnDenseBlocks) { expect_agreement(test::random_model(33, 0.6f, 4), 40000, 12); }
TEST(NanovdbHdda, AgreesWithDenseGridAtNegativeAndFarCoordinates) {
    expect_agreement(test::random_sparse(box3i{{-300, -20, 900}, {-100, 60, 1000}}, 3000, 5), 40000, 13);
}

TEST(NanovdbHdda, ReportsItsSizeAndSteps) {
    auto m = test::random_model(24, 0.1f, 6);
    vdb::hdda_scene s(m);
    EXPECT_GT(s.bytes(), m.voxel_count() * 4);  // at least the uint32 values of the leaves
    hit h = trace1(s, ray{{-10.5f, 5.5f, 5.5f}, 0.0f, {1, 0, 0}, inf});
    EXPECT_GT(h.steps, 0u);
}

}  // namespace
