// The per-lane stack of the dialect (kernels/stack.h) in every C++ lane set: random
// pushes, pops and overwrites at a different level in every lane, under random masks,
// read back level by level against one std::vector per lane. (The GPU dialects compile
// the same file into every OpenCL program and SPIR-V module at build time.)
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "voxray/check/ray_sets.hpp"
#include "voxray/cpu/lanes.hpp"

static_assert(VOXRAY_CPU_SIMD_LANES, "the SIMD lane sets are compiled in this file (tests/cpu/CMakeLists.txt)");

// run_stack_program(seed, rounds): the number of entries checked; fails the test on the
// first entry that differs. Defined once per lane namespace, in that namespace's ISA.
#define VOXRAY_STACK_PROGRAM                                                                              \
    inline std::size_t run_stack_program(std::uint64_t seed, int rounds) {                                \
        voxray::rng g(seed);                                                                              \
        vx_stack s;                                                                                       \
        std::memset(&s, 0, sizeof s);                                                                     \
        std::vector<std::vector<std::uint32_t>> expected(width);                                          \
        std::size_t checked = 0;                                                                          \
        for (int round = 0; round < rounds; ++round) {                                                    \
            std::int32_t levels[width], stores[width];                                                    \
            std::uint32_t values[width];                                                                  \
            for (int k = 0; k < width; ++k) {                                                             \
                auto& stack = expected[k];                                                                \
                int op = g.below(4); /* push, push, pop, overwrite the top */                             \
                values[k] = std::uint32_t(g.next());                                                      \
                levels[k] = 0, stores[k] = 0;                                                             \
                if (op < 2 && stack.size() < VX_STACK_DEPTH)                                              \
                    levels[k] = int(stack.size()), stack.push_back(values[k]), stores[k] = -1;            \
                else if (op == 2 && !stack.empty())                                                       \
                    stack.pop_back();                                                                     \
                else if (!stack.empty())                                                                  \
                    levels[k] = int(stack.size()) - 1, stack.back() = values[k], stores[k] = -1;          \
            }                                                                                             \
            vx_i32 level;                                                                                 \
            vx_u32 value;                                                                                 \
            std::memcpy(&level, levels, sizeof level);                                                    \
            std::memcpy(&value, values, sizeof value);                                                    \
            vx_i32 flags;                                                                                 \
            std::memcpy(&flags, stores, sizeof flags);                                                    \
            vx_mask m = flags != 0;                                                                       \
            vx_stack_store(s, level, value, m);                                                           \
            for (int d = 0; d < VX_STACK_DEPTH; ++d) {                                                    \
                vx_u32 got = vx_stack_load(s, vx_i32_splat(d));                                           \
                std::uint32_t lanes[width];                                                               \
                std::memcpy(lanes, &got, sizeof lanes);                                                   \
                for (int k = 0; k < width; ++k) {                                                         \
                    if (std::size_t(d) >= expected[k].size()) continue;                                   \
                    EXPECT_EQ(lanes[k], expected[k][d]) << "lane " << k << " depth " << d << " round " << round;\
                    if (lanes[k] != expected[k][d]) return checked;                                       \
                    ++checked;                                                                            \
                }                                                                                         \
            }                                                                                             \
        }                                                                                                 \
        return checked;                                                                                   \
    }

namespace voxray::kernels {
namespace scalar {
VOXRAY_STACK_PROGRAM
}
VOXRAY_AVX2_BEGIN
namespace simd8 {
VOXRAY_STACK_PROGRAM
}
VOXRAY_AVX2_END
VOXRAY_AVX512_BEGIN
namespace simd16 {
VOXRAY_STACK_PROGRAM
}
VOXRAY_AVX512_END
}  // namespace voxray::kernels

namespace {

using namespace voxray::kernels;

TEST(lane_stack, scalar_lanes_keep_every_level) { EXPECT_GT(scalar::run_stack_program(1, 3000), 10000u); }

TEST(lane_stack, eight_lanes_keep_every_level_of_every_lane) {
    if (!cpu_has_avx2()) GTEST_SKIP() << "no AVX2 on this CPU";
    EXPECT_GT(simd8::run_stack_program(2, 3000), 80000u);
}

TEST(lane_stack, sixteen_lanes_keep_every_level_of_every_lane) {
    if (!cpu_has_avx512()) GTEST_SKIP() << "no AVX-512 on this CPU";
    EXPECT_GT(simd16::run_stack_program(3, 3000), 160000u);
}

}  // namespace

