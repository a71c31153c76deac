// The SIMD lanes and the scalar path run the same kernel source: their results must be
// identical bit for bit (t included), on every ray.
#include <cstring>

#include <gtest/gtest.h>

#include "random_models.hpp"
#include "voxray/check/ray_sets.hpp"
#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"

using namespace voxray;

namespace {

void expect_bit_identical(const voxel_model& model, std::size_t count, std::uint64_t seed) {
    dense_grid grid(model);
    tracer<cpu, dense_grid> simd(grid);
    tracer<cpu_scalar, dense_grid> scalar(grid);
    auto rays = check_rays(model.bounds(), 2, count, seed);
    rays.push_back(ray{{NAN, 0, 0}, 0, {1, 0, 0}, INFINITY});  // a NaN lane inside a packet
    std::vector<hit> a(rays.size()), b(rays.size());
    for (int mode = 0; mode < 2; ++mode) {
        if (mode == 0) { simd.closest_hit(rays, a); scalar.closest_hit(rays, b); }
        else { simd.any_hit(rays, a); scalar.any_hit(rays, b); }
        std::size_t differ = 0;
        for (std::size_t i = 0; i < rays.size(); ++i)
            if (std::memcmp(&a[i], &b[i], sizeof(hit)) != 0) ++differ;
        EXPECT_EQ(differ, 0u) << "of " << rays.size() << " rays, mode " << mode;
    }
}

TEST(simd_vs_scalar, noise) { expect_bit_identical(test::random_model(40, 0.02f, 3), 20000, 21); }
TEST(simd_vs_scalar, hollow_box) { expect_bit_identical(test::hollow_box(30, {-7, 2, 0}), 20000, 22); }
TEST(simd_vs_scalar, odd_ray_counts_fill_partial_packets) {
    for (std::size_t n : {1u, 7u, 17u, 1023u, 1025u}) expect_bit_identical(test::random_model(12, 0.1f, 4), n, n);
}

}  // namespace
