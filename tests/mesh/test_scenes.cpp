// Built-in procedural scenes: determinism, exact Menger counts, bounds, spec errors.
#include <cstdint>
#include <set>

#include <gtest/gtest.h>

#include "mesh_test_util.hpp"
#include "voxray/scenes/builtin.hpp"

namespace {

using voxray::scenes::make_builtin;
using voxray::test::expect_error;
using voxray::test::model_hash;

TEST(Scenes, SameSpecGivesSameVoxelsForAnyThreadCount) {
    for (const char* spec : {"terrain:256:seed=3", "menger:81"}) {
        auto a = make_builtin(spec, 1), b = make_builtin(spec, 3);
        EXPECT_EQ(a.voxel_count(), b.voxel_count()) << spec;
        EXPECT_EQ(model_hash(a), model_hash(b)) << spec;
        EXPECT_EQ(a.chunk_count(), b.chunk_count()) << spec;
    }
}

TEST(Scenes, SeedChangesTerrain) {
    auto a = make_builtin("terrain:256:seed=1", 2), b = make_builtin("terrain:256:seed=2", 2);
    EXPECT_NE(model_hash(a), model_hash(b));
    auto d = make_builtin("terrain:256", 2);  // seed 1 is the default
    EXPECT_EQ(model_hash(a), model_hash(d));
}

TEST(Scenes, TerrainShape) {
    auto m = make_builtin("terrain:512:seed=4", 2);
    auto b = m.bounds();
    EXPECT_EQ(m.up_axis, 2);
    EXPECT_EQ(b.min, glm::ivec3(0));
    EXPECT_EQ(b.max.x, 512);
    EXPECT_EQ(b.max.y, 512);
    EXPECT_GT(b.max.z, 20);
    EXPECT_LT(b.max.z, 512);
    // Roughly a skin of a few voxels per column, plus cliffs, rim and buildings.
    EXPECT_GT(m.voxel_count(), 512u * 512u * 3u);
    EXPECT_LT(m.voxel_count(), 512u * 512u * 12u);
    // Every column is covered seen from above, and some facades exist.
    std::set<std::uint8_t> used;
    std::vector<char> covered(512 * 512, 0);
    m.for_each_voxel([&](glm::ivec3 p, std::uint8_t v) {
        used.insert(v);
        covered[std::size_t(p.y) * 512 + std::size_t(p.x)] = 1;
    });
    EXPECT_EQ(std::count(covered.begin(), covered.end(), 1), 512 * 512);
    bool facade = false;
    for (int i = 14; i < 20; ++i) facade |= used.count(std::uint8_t(i)) > 0;
    EXPECT_TRUE(facade) << "no buildings";
    for (auto v : used) {
        auto c = m.palette()[v].colour;
        EXPECT_TRUE(c.r || c.g || c.b) << "palette entry " << int(v) << " is unset";
    }
}

TEST(Scenes, MengerCountsAndBounds) {
    struct expect {
        const char* spec;
        int size;
        std::uint64_t voxels;
    };
    for (auto e : {expect{"menger:3", 3, 20}, expect{"menger:9", 9, 400}, expect{"menger:27", 27, 8000},
                   expect{"menger:81", 81, 160000}, expect{"menger:54", 54, 8000 * 8},
                   expect{"menger:21", 21, 20 * 343}}) {
        auto m = make_builtin(e.spec, 2);
        EXPECT_EQ(m.voxel_count(), e.voxels) << e.spec;
        EXPECT_EQ(m.bounds().min, glm::ivec3(0)) << e.spec;
        EXPECT_EQ(m.bounds().max, glm::ivec3(e.size)) << e.spec;
    }
    // Level 2, cell by cell against the definition.
    auto m = make_builtin("menger:9", 1);
    glm::ivec3 p;
    for (p.z = 0; p.z < 9; ++p.z)
        for (p.y = 0; p.y < 9; ++p.y)
            for (p.x = 0; p.x < 9; ++p.x) {
                bool hole = false;
                for (int d = 1; d <= 3; d *= 3) {
                    int ones = (p.x / d % 3 == 1) + (p.y / d % 3 == 1) + (p.z / d % 3 == 1);
                    hole |= ones >= 2;
                }
                EXPECT_EQ(m.get(p) != 0, !hole) << p.x << "," << p.y << "," << p.z;
            }
}

TEST(Scenes, DefaultMenger) {
    auto m = make_builtin("menger", 2);
    EXPECT_EQ(m.voxel_count(), 25600000u);  // level 5, 2-voxel cells
    EXPECT_EQ(m.bounds().max, glm::ivec3(486));
}

TEST(Scenes, BadSpecsThrow) {
    expect_error([] { make_builtin("forest"); }, "'forest'", "available: terrain, menger");
    expect_error([] { make_builtin(""); }, "available: terrain, menger");
    expect_error([] { make_builtin("terrain:abc"); }, "'abc'");
    expect_error([] { make_builtin("terrain:"); }, "empty size");
    expect_error([] { make_builtin("terrain:32"); }, "terrain size 32", "64..8192");
    expect_error([] { make_builtin("terrain:256:512"); }, "unexpected '512'");
    expect_error([] { make_builtin("terrain:256:bogus=1"); }, "no option 'bogus'", "seed, skin");
    expect_error([] { make_builtin("terrain:256:seed=-1"); }, "seed", "'-1'");
    expect_error([] { make_builtin("terrain:256:skin=0"); }, "skin 0");
    expect_error([] { make_builtin("menger:100"); }, "menger size 100");
    expect_error([] { make_builtin("menger:1"); }, "menger size 1");
    expect_error([] { make_builtin("menger:729:seed=1"); }, "no option 'seed'");
    expect_error([] { make_builtin("menger:2187"); }, "menger voxel count", "limit");
}

}  // namespace
