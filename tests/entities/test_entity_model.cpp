// The entity model record (entities/entity_model.hpp, layout.h) on the host: every empty
// brick's distance field names an empty cuboid grown as far as it may go, and a record
// without fields says so.
#include <gtest/gtest.h>

#include "scene_cases.hpp"

namespace voxray {
namespace {

using namespace voxray::test;

// Which 4^3 bricks of model m hold a solid voxel, read voxel by voxel through get().
struct solid_bricks {
    glm::ivec3 n;
    std::vector<std::uint8_t> solid;
    explicit solid_bricks(const entity_model& m)
        : n((m.extent() + (VX_EM_BRICK_EDGE - 1)) / VX_EM_BRICK_EDGE), solid(std::size_t(n.x) * n.y * n.z, 0) {
        glm::ivec3 e = m.extent();
        for (int z = 0; z < e.z; ++z)
            for (int y = 0; y < e.y; ++y)
                for (int x = 0; x < e.x; ++x)
                    if (m.get(m.bounds().min + glm::ivec3(x, y, z)) != 0)
                        solid[std::size_t(x / 4) + std::size_t(n.x) * (y / 4 + std::size_t(n.y) * (z / 4))] = 1;
    }
    // Whether any brick of [lo, hi) is solid.
    bool any(glm::ivec3 lo, glm::ivec3 hi) const {
        for (int z = lo.z; z < hi.z; ++z)
            for (int y = lo.y; y < hi.y; ++y)
                for (int x = lo.x; x < hi.x; ++x)
                    if (solid[std::size_t(x) + std::size_t(n.x) * (y + std::size_t(n.y) * z)]) return true;
        return false;
    }
};

TEST(entity_model, brick_fields_are_empty_cuboids_grown_until_blocked) {
    std::vector<voxel_model> models = test_models();
    models.push_back(random_model(37, 0.002f, 5, {3, -8, 1}));  // extents not a multiple of 4
    models.push_back(sphere_shell(30));                         // a large empty inside
    voxel_model row;                                            // 76 bricks long: fields reach the cap
    row.set({0, 0, 0}, 1);
    row.set({300, 2, 1}, 2);
    models.push_back(std::move(row));
    int capped = 0, blocked = 0;
    for (auto& vm : models) {
        entity_model m(vm);
        ASSERT_TRUE(m.has_fields());
        solid_bricks truth(m);
        glm::ivec3 nb = truth.n;
        for (int z = 0; z < nb.z; ++z)
            for (int y = 0; y < nb.y; ++y)
                for (int x = 0; x < nb.x; ++x) {
                    glm::ivec3 b(x, y, z);
                    std::uint32_t word = m.brick_word(b);
                    bool solid = truth.any(b, b + 1);
                    ASSERT_EQ(word == VX_EM_BRICK_SOLID, solid) << "brick " << x << " " << y << " " << z;
                    if (solid) continue;
                    glm::ivec3 lo = b, hi = b + 1;
                    for (int a = 0; a < 3; ++a) {
                        hi[a] += int(VX_EM_FIELD(word, 2u * unsigned(a)));
                        lo[a] -= int(VX_EM_FIELD(word, 2u * unsigned(a) + 1u));
                    }
                    ASSERT_TRUE(glm::all(glm::greaterThanEqual(lo, glm::ivec3(0))) && glm::all(glm::lessThanEqual(hi, nb)));
                    ASSERT_FALSE(truth.any(lo, hi)) << "brick " << x << " " << y << " " << z;
                    // Each direction stopped at the cap, the grid's side, or a slab holding a
                    // solid brick (a slab only widens after its direction stopped).
                    for (unsigned dir = 0; dir < 6; ++dir) {
                        int a = int(dir / 2);
                        if (VX_EM_FIELD(word, dir) == VX_EM_FIELD_MAX) {
                            ++capped;
                            continue;
                        }
                        glm::ivec3 slab_lo = lo, slab_hi = hi;
                        if (dir % 2 == 0) slab_lo[a] = hi[a], slab_hi[a] = hi[a] + 1;
                        else slab_lo[a] = lo[a] - 1, slab_hi[a] = lo[a];
                        if (slab_lo[a] < 0 || slab_hi[a] > nb[a]) continue;
                        ++blocked;
                        ASSERT_TRUE(truth.any(slab_lo, slab_hi)) << "brick " << x << " " << y << " " << z << " dir " << dir;
                    }
                }
    }
    EXPECT_GT(capped, 0);
    EXPECT_GT(blocked, 0);
}

TEST(entity_model, records_without_fields_say_so) {
    entity_model m(hollow_box(20), model_fields::none);
    EXPECT_FALSE(m.has_fields());
    EXPECT_EQ(m.words()[VX_EM_BRICKS], 0u);
    EXPECT_LT(m.words().size(), entity_model(hollow_box(20)).words().size());
}

}  // namespace
}  // namespace voxray
