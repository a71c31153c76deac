// Precomputed shadows (appearance/shadows.hpp): a wall behind a one-voxel blocker gets the
// blocker's transmittance, a voxel does not shadow itself within the skip distance, the walk
// lights a voxel by its visibility, shadows for another light are refused, the same bytes
// for 1 and 2 threads, and table files keep them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <string>

#include "error_of.hpp"
#include "temp_dir.hpp"
#include "voxray/appearance/shadows.hpp"
#include "voxray/appearance/table_file.hpp"
#include "voxray/cpu/appearance_walk.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "walk_tables.hpp"

namespace voxray {
namespace {

using namespace appearance;
using shadow_walker = appearance_walker<kernels::dense_grid_kernel>;

// A 16 x 16 wall at z = 8 and a 5 x 5 blocker one voxel thick at z = 3, in front of the
// wall's middle. The light is towards -z: the blocker shadows the wall's middle.
voxel_model wall_and_blocker() {
    voxel_model m;
    for (int y = 0; y < 16; ++y)
        for (int x = 0; x < 16; ++x) m.set({x, y, 8}, 1);
    for (int y = 5; y < 10; ++y)
        for (int x = 5; x < 10; ++x) m.set({x, y, 3}, 2);
    return m;
}

const glm::vec3 towards_minus_z{0.0f, 0.0f, -1.0f};

struct shadowed_scene {
    voxel_model model = wall_and_blocker();
    dense_grid grid{model};
    appearance_table table;

    // Every record of opacity q / 15 (test::uniform_table: faces turned to -z).
    explicit shadowed_scene(std::uint32_t q, float skip = 1.5f) : table(test::uniform_table(model, q)) {
        shadow_walker walker({grid.blob().begin(), grid.blob().end()}, table, 1);
        precompute_shadows(walker, table, towards_minus_z, {.skip = skip, .threads = 2});
    }
    int visibility(glm::ivec3 v) const { return table.shadows->visibility[*table.row_of(v)]; }
};

TEST(appearance_shadows, a_wall_behind_a_blocker_gets_its_transmittance) {
    shadowed_scene s(8);  // opacity 8/15: transmittance 7/15
    const int through_blocker = int(std::lround(255.0 * 7.0 / 15.0));
    EXPECT_NEAR(s.visibility({7, 7, 8}), through_blocker, 1);
    EXPECT_NEAR(s.visibility({5, 9, 8}), through_blocker, 1);
    EXPECT_EQ(s.visibility({4, 7, 8}), 255);   // beside the blocker's shadow
    EXPECT_EQ(s.visibility({15, 0, 8}), 255);
    EXPECT_EQ(s.visibility({7, 7, 3}), 255);   // nothing between the blocker and the light
    shadowed_scene opaque(15);
    EXPECT_EQ(opaque.visibility({7, 7, 8}), 0);
    EXPECT_EQ(opaque.visibility({4, 7, 8}), 255);
}

TEST(appearance_shadows, a_voxel_does_not_shadow_itself_within_the_skip) {
    // From the centre (skip 0) each voxel's own opacity counts: 7/15 left everywhere, and
    // (7/15)^2 behind the blocker (two layers apart).
    shadowed_scene s(8, 0.0f);
    EXPECT_NEAR(s.visibility({4, 7, 8}), std::lround(255.0 * 7.0 / 15.0), 1);
    EXPECT_NEAR(s.visibility({7, 7, 3}), std::lround(255.0 * 7.0 / 15.0), 1);
    EXPECT_NEAR(s.visibility({7, 7, 8}), std::lround(255.0 * 49.0 / 225.0), 1);
}

TEST(appearance_shadows, the_walk_lights_a_voxel_by_its_visibility) {
    shadowed_scene s(15);
    const appearance_table plain = test::uniform_table(s.model, 15);
    const std::vector<std::uint32_t> blob(s.grid.blob().begin(), s.grid.blob().end());
    shadow_walker with(blob, s.table, 2), without(blob, plain, 2);
    // Rays from between the blocker and the wall, straight at the wall (the faces look at
    // them and at the light: n . l = 1): one into the shadow, one beside it.
    std::vector<ray> rays(2);
    rays[0].origin = {6.5f, 6.5f, 6.0f}, rays[1].origin = {1.5f, 1.5f, 6.0f};  // red 222 and 37
    for (ray& r : rays) r.direction = {0.0f, 0.0f, 1.0f}, r.tmin = 0.0f;
    const appearance_light light{.to_light = towards_minus_z, .ambient = 0.2f};
    std::vector<appearance_pixel> lit = with.walk(rays, light), unlit = without.walk(rays, light);
    for (const auto& p : lit) ASSERT_TRUE(p.is_hit());
    EXPECT_NEAR(lit[0].r, 0.2f * unlit[0].r, 1e-6f);  // in the shadow: the ambient alone
    EXPECT_GT(unlit[0].r, 0.1f);
    EXPECT_EQ(lit[1].r, unlit[1].r);                   // visibility 255: as without shadows
    // Without shadows on request, and for another light only then.
    appearance_light off = light;
    off.shadows = false;
    EXPECT_EQ(with.walk(rays, off)[0].r, unlit[0].r);
    appearance_light other = off;
    other.to_light = {0.0f, 1.0f, 0.0f};
    EXPECT_NO_THROW(with.walk(rays, other));
    other.shadows = true;
    std::string refused = test::error_of([&] { with.walk(rays, other); });
    EXPECT_NE(refused.find("shadows are for the light towards (0, 0, -1)"), std::string::npos) << refused;
}

TEST(appearance_shadows, the_same_bytes_for_one_and_two_threads) {
    voxel_model m;  // a third of a 20^3 box, scattered: many partial shadows
    for (int z = 0; z < 20; ++z)
        for (int y = 0; y < 20; ++y)
            for (int x = 0; x < 20; ++x)
                if ((std::uint32_t(x * 73856093 ^ y * 19349663 ^ z * 83492791) >> 7) % 3 == 0) m.set({x, y, z}, 1);
    dense_grid grid(m);
    appearance_table one = test::uniform_table(m, 6), two = one;
    shadow_walker walker({grid.blob().begin(), grid.blob().end()}, one, 2);
    const glm::vec3 light = glm::normalize(glm::vec3(0.4f, 1.0f, -0.3f));
    precompute_shadows(walker, one, light, {.threads = 1});
    precompute_shadows(walker, two, light, {.threads = 2});
    EXPECT_EQ(one.shadows->visibility, two.shadows->visibility);
    std::size_t partial = 0;
    for (std::uint8_t v : one.shadows->visibility) partial += v > 0 && v < 255;
    EXPECT_GT(partial, one.size() / 4);
}

TEST(appearance_shadows, bad_lights_and_table_files) {
    shadowed_scene s(8);
    shadow_walker walker({s.grid.blob().begin(), s.grid.blob().end()}, s.table, 1);
    appearance_table t = s.table;
    std::string not_unit = test::error_of([&] { precompute_shadows(walker, t, {0.0f, 2.0f, 0.0f}); });
    EXPECT_NE(not_unit.find("(0, 2, 0) is not a unit vector"), std::string::npos) << not_unit;

    test::temp_dir dir;
    std::filesystem::path p = dir.path / "shadowed.vxap";
    save_table(s.table, p);
    appearance_table back = load_table(p);
    ASSERT_TRUE(back.shadows);
    EXPECT_EQ(back.shadows->to_light, towards_minus_z);
    EXPECT_EQ(back.shadows->visibility, s.table.shadows->visibility);
    EXPECT_EQ(back.words, s.table.words);
    // A version 1 file cannot say it has shadows.
    std::ifstream in(p, std::ios::binary);
    std::vector<char> bytes{std::istreambuf_iterator<char>(in), {}};
    in.close();
    bytes[4] = 1;
    std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
    std::string v1 = test::error_of([&] { load_table(p); });
    EXPECT_NE(v1.find("offset 40: shadows flag is 1 (0 in version 1)"), std::string::npos) << v1;
    // Shadows for another number of rows.
    appearance_table wrong = s.table;
    wrong.shadows->visibility.pop_back();
    std::string rows = test::error_of([&] { save_table(wrong, p); });
    EXPECT_NE(rows.find("shadows of " + std::to_string(s.table.size() - 1) + " rows"), std::string::npos) << rows;
}

}  // namespace
}  // namespace voxray
