// The reference grid against a brute-force slab test over every voxel: an oracle that
// shares no code with the DDA. Zero mismatches; ties (edges, corners) are counted.
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "brute_force.hpp"
#include "random_models.hpp"
#include "voxray/check/compare.hpp"
#include "voxray/check/ray_sets.hpp"
#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"

using namespace voxray;

namespace {

std::string describe(const ray& r) {
    std::ostringstream s;
    s << "o=(" << r.origin.x << ", " << r.origin.y << ", " << r.origin.z << ") d=(" << r.direction.x << ", "
      << r.direction.y << ", " << r.direction.z << ") t=[" << r.tmin << ", " << r.tmax << "]";
    return s.str();
}

std::string describe(const hit& h) {
    std::ostringstream s;
    s << (h.is_hit() ? "hit" : "miss") << " t=" << h.t << " voxel=(" << h.voxel.x << ", " << h.voxel.y << ", "
      << h.voxel.z << ") face=" << face_name(h.normal) << " material=" << h.material;
    return s.str();
}

agreement_counts against_brute_force(const voxel_model& model, std::size_t rays_count, std::uint64_t seed) {
    dense_grid grid(model);
    tracer<cpu_scalar, dense_grid> t(grid);
    auto rays = check_rays(model.bounds(), 2, rays_count, seed);
    std::vector<hit> hits(rays.size());
    t.closest_hit(rays, hits);
    agreement_counts counts;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        hit expected = test::brute_force_trace(model, rays[i]);
        auto a = compare_hits(rays[i], expected, hits[i]);
        counts.add(a);
        EXPECT_NE(a, agreement::mismatch) << "ray " << i << ": " << describe(rays[i]) << "\n  oracle " << describe(expected)
                                          << "\n  grid   " << describe(hits[i]);
    }
    return counts;
}

TEST(dense_oracle, sparse_noise) {
    auto counts = against_brute_force(test::random_model(20, 0.05f, 1), 4000, 11);
    EXPECT_EQ(counts.mismatches, 0u);
    EXPECT_LT(counts.ties, counts.rays / 50) << "ties should be rare edge/corner cases";
}

TEST(dense_oracle, dense_noise_with_negative_coordinates) {
    auto counts = against_brute_force(test::random_model(16, 0.3f, 2, {-9, -3, -20}), 4000, 12);
    EXPECT_EQ(counts.mismatches, 0u);
}

TEST(dense_oracle, hollow_box_from_inside_and_outside) {
    auto counts = against_brute_force(test::hollow_box(18, {5, 5, 5}), 4000, 13);
    EXPECT_EQ(counts.mismatches, 0u);
}

TEST(dense_oracle, solid_block) {
    auto counts = against_brute_force(test::solid_block({-4, 0, 2}, {9, 7, 12}), 4000, 14);
    EXPECT_EQ(counts.mismatches, 0u);
}

}  // namespace
