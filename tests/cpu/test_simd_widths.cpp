// Both SIMD lane sets of voxray::cpu (8 lanes: AVX2; 16 lanes: AVX-512, where the CPU has
// it) give the scalar kernel's hits bit for bit, on every registered structure, for
// closest and any hit. The conformance suite runs `cpu` at the width the CPU picks; this
// pins each width, so the one not picked is tested too.
#include <gtest/gtest.h>

#include <cstring>

#include "random_models.hpp"
#include "voxray/check/ray_sets.hpp"
#include "voxray/core/type_list.hpp"
#include "voxray/cpu.hpp"
#include "voxray/generated/structures.hpp"

namespace {

using namespace voxray;

template <class Structure>
void expect_widths_agree(unsigned width) {
    for (auto [density, seed] : {std::pair{0.05f, 3u}, std::pair{0.3f, 4u}}) {
        voxel_model model = test::random_model(37, density, seed, {-5, 3, -9});
        Structure s(model);
        auto rays = check_rays(model.bounds(), 2, 5003, seed);  // odd count: partial lane groups
        tracer<cpu_scalar, Structure> scalar(s);
        tracer<cpu, Structure> lanes(s, cpu_options{0, width});
        ASSERT_EQ(lanes.engine().simd_width(), width);
        for (bool any : {false, true}) {
            std::vector<hit> expected(rays.size()), got(rays.size());
            if (any) scalar.any_hit(rays, expected), lanes.any_hit(rays, got);
            else scalar.closest_hit(rays, expected), lanes.closest_hit(rays, got);
            std::size_t differ = 0;
            for (std::size_t i = 0; i < rays.size(); ++i)
                differ += std::memcmp(&expected[i], &got[i], sizeof(hit)) != 0;
            EXPECT_EQ(differ, 0u) << Structure::name << ", " << width << " lanes, " << (any ? "any" : "closest")
                                  << " hit, density " << density;
        }
    }
}

void for_each_structure(unsigned width) {
    for_each_type(registered::structures{}, [&]<class S>() { expect_widths_agree<S>(width); });
}

TEST(simd_widths, eight_lanes_match_scalar) {
    if (!kernels::cpu_has_avx2()) GTEST_FAIL() << "this CPU has no AVX2: the 8-lane set cannot run here";
    for_each_structure(8);
}

TEST(simd_widths, sixteen_lanes_match_scalar) {
    // A CPU without AVX-512 cannot run the 16-lane set; asking for it must be an error.
    if (!kernels::cpu_has_avx512()) {
        dense_grid g(test::single_voxel({0, 0, 0}));
        EXPECT_THROW((tracer<cpu, dense_grid>(g, cpu_options{0, 16})), voxray::error);
        return;
    }
    for_each_structure(16);
}

TEST(simd_widths, other_widths_are_rejected) {
    dense_grid g(test::single_voxel({0, 0, 0}));
    EXPECT_THROW((tracer<cpu, dense_grid>(g, cpu_options{0, 4})), voxray::error);
}

}  // namespace
