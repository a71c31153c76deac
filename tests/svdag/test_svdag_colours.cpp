// The DAG with Aokana's colour blocks, on every backend: the geometry of every hit is the
// reference's (voxel, t, face), and its colour is within the stated error of the palette
// colour of the reference's material; the build's own error figures agree with that; and
// a larger error merges more voxels into fewer blocks.
#include <gtest/gtest.h>

#include <limits>
#include <string>

#include "every_backend.hpp"
#include "random_models.hpp"
#include "special_rays.hpp"
#include "voxray/check/compare.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/scenes/builtin.hpp"
#include "voxray/svdag/svdag.hpp"
#include "voxray/tracer.hpp"

namespace voxray {
namespace {

using namespace voxray::test;
using scenes::make_builtin;

// Terrain painted with a ramp: materials follow the position, and the palette maps
// neighbouring indices to neighbouring colours, so blocks really average (and err).
voxel_model coloured_terrain() {
    voxel_model model = make_builtin("terrain:96", 2);
    std::vector<glm::ivec3> solid;
    model.for_each_voxel([&](glm::ivec3 p, std::uint8_t) { solid.push_back(p); });
    for (auto p : solid) model.set(p, std::uint8_t(1 + (p.x + p.y + 2 * p.z) % 254));
    for (int i = 1; i < 256; ++i)
        model.palette()[std::uint8_t(i)].colour = rgba{std::uint8_t(i), std::uint8_t(255 - i), std::uint8_t(i / 2), 255};
    return model;
}

template <class Backend>
struct svdag_colours_on : ::testing::Test {};
TYPED_TEST_SUITE(svdag_colours_on, every_backend, backend_names);

TYPED_TEST(svdag_colours_on, hits_carry_colours_within_the_error) {
    using Backend = TypeParam;
    const char* backend = Backend::name;
    voxel_model model = coloured_terrain();
    svdag_options o;
    o.colour_error = 0.05f;
    svdag_colours dag(model, o);
    ASSERT_GT(dag.stats().colour_blocks, 0u);
    EXPECT_LE(dag.stats().colour_error_max, svdag_build::colour_tolerance(o.colour_error));

    dense_grid grid(model);
    auto rays = mixed_rays(model.bounds(), 20000, 9);
    std::vector<hit> expected(rays.size()), got(rays.size());
    tracer<cpu_scalar, dense_grid>(grid, cpu_options{1}).closest_hit(rays, expected);
    tracer<Backend, svdag_colours>(dag).closest_hit(rays, got);
    std::size_t compared = 0, mismatches = 0;
    double worst = 0;
    double tolerance = dag.colour_tolerance();
    for (std::size_t i = 0; i < rays.size(); ++i) {
        if (expected[i].is_hit() && got[i].is_hit() && expected[i].voxel == got[i].voxel) {
            worst = std::max(worst, colour_difference(got[i].material, model.palette()[std::uint8_t(expected[i].material)].colour));
            ++compared;
        }
        if (compare_colour_hits(rays[i], expected[i], got[i], model.palette(), tolerance) == agreement::mismatch) ++mismatches;
    }
    EXPECT_EQ(mismatches, 0u) << backend;
    EXPECT_GT(compared, rays.size() / 4) << backend;
    EXPECT_LE(worst, svdag_build::colour_tolerance(o.colour_error)) << backend;
    EXPECT_GT(worst, 0.5 * o.colour_error) << backend << ": blocks this long should average colours apart";
    std::printf("[%s] %zu colours compared, worst channel error %.4f (blocks: %llu for %llu voxels)\n", backend,
                compared, worst, (unsigned long long)dag.stats().colour_blocks,
                (unsigned long long)model.voxel_count());
}

TEST(svdag_colours, an_error_outside_0_1_says_so) {
    voxel_model model = make_builtin("menger:27", 1);
    for (float e : {-0.1f, 1.5f, std::numeric_limits<float>::quiet_NaN()}) {
        svdag_options o;
        o.colour_error = e;
        try {
            svdag_colours dag(model, o);
            ADD_FAILURE() << "colour_error " << e << " was accepted";
        } catch (const std::exception& x) {
            EXPECT_NE(std::string(x.what()).find("is outside [0, 1]"), std::string::npos) << x.what();
        }
    }
}

TEST(svdag_colours, a_larger_error_gives_fewer_blocks) {
    voxel_model model = coloured_terrain();
    std::uint64_t previous = UINT64_MAX;
    for (float e : {0.0f, 0.02f, 0.05f, 0.2f}) {
        svdag_options o;
        o.colour_error = e;
        svdag_colours dag(model, o);
        EXPECT_LE(dag.stats().colour_error_max, svdag_build::colour_tolerance(e)) << e;
        EXPECT_LE(dag.stats().colour_blocks, previous) << e;
        previous = dag.stats().colour_blocks;
    }
    EXPECT_LT(previous, model.voxel_count() / 4) << "blocks at e = 0.2 should be long";
}

}  // namespace
}  // namespace voxray
