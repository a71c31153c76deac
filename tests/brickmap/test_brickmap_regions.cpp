// Edit regions at the ends of int coordinates: radii of INT_MAX, capsules and lines from
// INT_MIN to INT_MAX. Exact, free of signed overflow (the ASan+UBSan pass runs this
// label), and clipped to the world in time proportional to the world, not the region.
#include <climits>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "voxray/brickmap/brickmap.hpp"

using namespace voxray;

namespace {

const box3i world64{{0, 0, 0}, {64, 64, 64}};

brickmap<> clipped() { return brickmap<>(world64, {.outside = outside_edits::clip}); }

// Points (dy, dz) with dy^2 + dz^2 <= r^2: the cross-section of a straight capsule.
std::uint64_t disc(int r) {
    std::uint64_t n = 0;
    for (int y = -r; y <= r; ++y)
        for (int z = -r; z <= r; ++z) n += y * y + z * z <= r * r;
    return n;
}

}  // namespace

TEST(BrickmapRegions, HugeRadiiFillTheWholeClippedWorld) {
    auto m = clipped();
    m.fill_sphere({32, 32, 32}, INT_MAX, 5, 2);
    EXPECT_EQ(m.voxel_count(), 262144u);
    m.erase_sphere({INT_MIN, INT_MIN, INT_MIN}, INT_MAX);  // 2^31 from the world on each axis: misses
    EXPECT_EQ(m.voxel_count(), 262144u);
    auto c = clipped();
    c.apply(regions::capsule{{1, 2, 3}, {60, 50, 40}, INT_MAX}, edit_op::fill, 3, 2);
    EXPECT_EQ(c.voxel_count(), 262144u);
}

TEST(BrickmapRegions, CapsulesAndLinesAcrossAllOfIntCoordinates) {
    auto m = clipped();
    m.apply(regions::capsule{{INT_MIN, 32, 32}, {INT_MAX, 32, 32}, 3}, edit_op::fill, 4, 2);
    EXPECT_EQ(m.voxel_count(), 64 * disc(3));
    EXPECT_EQ(m.get({0, 35, 32}), 4);
    EXPECT_EQ(m.get({63, 32, 29}), 4);
    EXPECT_EQ(m.get({10, 35, 33}), 0);
    auto diagonal = clipped();  // all three axes from one end of int to the other
    diagonal.apply(regions::capsule{{INT_MIN, INT_MIN, INT_MIN}, {INT_MAX, INT_MAX, INT_MAX}, 1}, edit_op::fill, 6);
    EXPECT_EQ(diagonal.get({7, 7, 7}), 6);
    EXPECT_EQ(diagonal.get({7, 9, 7}), 0);
    auto line = clipped();
    line.apply_line({-2000000000, 5, 9}, {2000000000, 5, 9}, 0, edit_op::fill, 7);
    EXPECT_EQ(line.voxel_count(), 64u);
    EXPECT_EQ(line.get({0, 5, 9}), 7);
    EXPECT_EQ(line.get({63, 5, 9}), 7);
}

// The clipped walk visits exactly the voxels of the full walk inside the box, in order.
TEST(BrickmapRegions, ClippedLineWalkEqualsTheFilteredFullWalk) {
    std::mt19937 g(5);
    box3i clip{{-7, 2, -3}, {20, 25, 11}};
    for (int k = 0; k < 3000; ++k) {
        auto coord = [&] { return int(g() % 80) - 30; };
        glm::ivec3 a(coord(), coord(), coord()), b(coord(), coord(), coord());
        std::vector<glm::ivec3> full, part;
        regions::line_voxels(a, b, [&](glm::ivec3 p) {
            if (clip.contains(p)) full.push_back(p);
        });
        regions::line_voxels_in(a, b, clip, [&](glm::ivec3 p) { part.push_back(p); });
        ASSERT_EQ(full, part) << "line " << a.x << "," << a.y << "," << a.z << " -> " << b.x << "," << b.y << "," << b.z;
    }
}

// The capsule's 256-bit comparison agrees with a plain 64-bit one where that cannot overflow.
TEST(BrickmapRegions, CapsuleMembershipMatchesSmallIntegerArithmetic) {
    std::mt19937 g(8);
    for (int k = 0; k < 20000; ++k) {
        auto coord = [&] { return int(g() % 200) - 100; };
        regions::capsule c{{coord(), coord(), coord()}, {coord(), coord(), coord()}, int(g() % 30)};
        glm::ivec3 p(coord(), coord(), coord());
        glm::i64vec3 ab = glm::i64vec3(c.b - c.a), ap = glm::i64vec3(p - c.a), bp = glm::i64vec3(p - c.b);
        std::int64_t len2 = ab.x * ab.x + ab.y * ab.y + ab.z * ab.z, t = ap.x * ab.x + ap.y * ab.y + ap.z * ab.z;
        std::int64_t r2 = std::int64_t(c.radius) * c.radius, ap2 = ap.x * ap.x + ap.y * ap.y + ap.z * ap.z;
        bool want = len2 == 0 || t <= 0 ? ap2 <= r2
                  : t >= len2           ? bp.x * bp.x + bp.y * bp.y + bp.z * bp.z <= r2
                                        : ap2 * len2 - t * t <= r2 * len2;
        ASSERT_EQ(c.contains(p), want) << k;
    }
}
