// Fills that reach outside a brickmap's world box: the world grows to hold them (the
// default), or the edit fails with a clear error and changes nothing, or (opt-in) it is
// clipped. Never a silently flattened sphere.
#include <climits>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "voxray/brickmap/brickmap.hpp"

using namespace voxray;

namespace {

// Voxels of a sphere counted by brute force over its bounds.
std::uint64_t sphere_voxels(const regions::sphere& s) {
    std::uint64_t n = 0;
    box3i b = s.bounds();
    for (int z = b.min.z; z < b.max.z; ++z)
        for (int y = b.min.y; y < b.max.y; ++y)
            for (int x = b.min.x; x < b.max.x; ++x) n += s.contains({x, y, z});
    return n;
}

template <class Map>
std::uint64_t solid_in(const Map& m, box3i b) {
    std::uint64_t n = 0;
    for (int z = b.min.z; z < b.max.z; ++z)
        for (int y = b.min.y; y < b.max.y; ++y)
            for (int x = b.min.x; x < b.max.x; ++x) n += m.get({x, y, z}) != 0;
    return n;
}

std::string message_of(auto&& f) {
    try {
        f();
    } catch (const error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(BrickmapBounds, SphereCrossingTheTopGrowsTheWorldAndStaysRound) {
    box3i world{{-3, 0, 5}, {61, 64, 69}};
    brickmap<> m(world);
    m.fill_box({{0, 0, 10}, {40, 8, 50}}, 4);  // ground that must survive the growth
    std::uint64_t ground = m.voxel_count();
    regions::sphere s{{30, 60, 30}, 12};  // its top 8 layers lie above y = 64
    m.fill_sphere(s.centre, s.radius, 9, 2);
    box3i b = m.bounds();
    EXPECT_LE(b.min.y, world.min.y);
    EXPECT_GE(b.max.y, 73);
    EXPECT_EQ(solid_in(m, s.bounds()), sphere_voxels(s));
    EXPECT_EQ(m.get({30, 72, 30}), 9);  // the top voxel of the sphere
    EXPECT_EQ(m.voxel_count(), ground + sphere_voxels(s));
    EXPECT_EQ(m.get({0, 0, 10}), 4);
    EXPECT_EQ(m.get({39, 7, 49}), 4);
}

TEST(BrickmapBounds, SphereWhollyOutsideBelowTheOriginIsAddedAndUploaded) {
    brickmap<std::uint16_t, 4> m(box3i{{0, 0, 0}, {32, 32, 32}});
    m.fill_box({{1, 1, 1}, {9, 9, 9}}, 3);
    (void)m.take_dirty_ranges();
    regions::sphere s{{-300, 10, -41}, 7};  // moves the min corner by several pages
    m.fill_sphere(s.centre, s.radius, 700);
    EXPECT_EQ(m.voxel_count(), 512 + sphere_voxels(s));
    EXPECT_EQ(solid_in(m, s.bounds()), sphere_voxels(s));
    EXPECT_EQ(m.get({-300, 10, -41}), 700);
    EXPECT_EQ(m.get({8, 8, 8}), 3);
    EXPECT_EQ(m.get({9, 9, 9}), 0);
    EXPECT_LE(m.bounds().min.x, -307);
    (void)m.snapshot();  // moves the dirty set into the change log: still whole for the next take
    EXPECT_TRUE(m.whole_blob_dirty());
    auto ranges = m.take_dirty_ranges();
    EXPECT_FALSE(m.whole_blob_dirty());
    ASSERT_EQ(ranges.size(), 1u);  // the blob was re-laid out: all of it goes
    EXPECT_EQ(ranges[0].count, m.blob().size());
    EXPECT_EQ(std::int32_t(m.blob()[VX_BM_HEADER_ORIGIN]), m.bounds().min.x);
}

TEST(BrickmapBounds, SetAndLinesAndBatchesGrow) {
    brickmap<> m(box3i{{0, 0, 0}, {16, 16, 16}});
    m.set({100, -20, 7}, 5);
    EXPECT_EQ(m.get({100, -20, 7}), 5);
    m.apply_line({0, 0, 0}, {-40, 3, 2}, 0, edit_op::fill, 6);
    EXPECT_EQ(m.get({-40, 3, 2}), 6);
    brickmap<>::edit edits[] = {{regions::box{{{500, 0, 0}, {504, 4, 4}}}, edit_op::fill, 7},
                                {regions::sphere{{-200, 0, 0}, 3}, edit_op::fill, 8}};
    m.apply_batch(edits, 2);
    EXPECT_EQ(m.get({503, 3, 3}), 7);
    EXPECT_EQ(m.get({-203, 0, 0}), 8);
    m.copy_region({{-203, 0, 0}, {-196, 1, 1}}, {0, 0, 900});
    EXPECT_EQ(m.get({-203, 0, 900}), 8);
    std::uint64_t expected = 1 + 41 + 64 + sphere_voxels({{-200, 0, 0}, 3}) + 7;
    EXPECT_EQ(m.voxel_count(), expected);
}

TEST(BrickmapBounds, GrowthPastThirtyTwoBitCoordinatesIsAClearErrorAndChangesNothing) {
    brickmap<> m(box3i{{0, 0, 0}, {64, 64, 64}});
    m.fill_box({{0, 0, 0}, {4, 4, 4}}, 1);
    auto blob = std::vector<std::uint32_t>(m.blob().begin(), m.blob().end());
    std::string what = message_of([&] { m.fill_sphere({32, 32, 32}, INT_MAX, 5); });
    EXPECT_NE(what.find("32-bit voxel coordinates"), std::string::npos) << what;
    EXPECT_NE(what.find("2147483647"), std::string::npos) << what;
    EXPECT_EQ(m.voxel_count(), 64u);
    EXPECT_EQ(m.bounds().max, glm::ivec3(64));
    EXPECT_TRUE(std::equal(blob.begin(), blob.end(), m.blob().begin(), m.blob().end()));
}

TEST(BrickmapBounds, FailPolicyRefusesWithTheRegionAndTheWorld) {
    brickmap<> m(box3i{{0, 0, 0}, {64, 64, 64}}, {.outside = outside_edits::fail});
    m.fill_sphere({32, 32, 32}, 5, 2);
    std::string what = message_of([&] { m.fill_sphere({32, 60, 32}, 6, 3); });
    EXPECT_NE(what.find("outside the world [(0, 0, 0), (64, 64, 64))"), std::string::npos) << what;
    EXPECT_NE(what.find("(26, 54, 26)"), std::string::npos) << what;
    EXPECT_EQ(m.voxel_count(), sphere_voxels({{32, 32, 32}, 5}));
    EXPECT_FALSE(message_of([&] { m.set({64, 0, 0}, 1); }).empty());
    m.erase_sphere({32, 60, 32}, 40);  // erasing needs no room: nothing is outside
    EXPECT_EQ(m.voxel_count(), 0u);
}

TEST(BrickmapBounds, ClipPolicyCutsAtTheWorldAsAsked) {
    brickmap<> m(box3i{{0, 0, 0}, {64, 64, 64}}, {.outside = outside_edits::clip});
    m.fill_sphere({32, 60, 32}, 8, 3);
    EXPECT_EQ(m.bounds().max, glm::ivec3(64));
    EXPECT_EQ(solid_in(m, {{0, 0, 0}, {64, 64, 64}}), m.voxel_count());
    EXPECT_LT(m.voxel_count(), sphere_voxels({{32, 60, 32}, 8}));
    m.set({70, 0, 0}, 1);  // outside: clipped away as well
    EXPECT_EQ(m.get({70, 0, 0}), 0);
}

// Threads fill spheres on every side of a small world at once: each fill grows the world
// (the exclusive lock moves the origin) while the others edit bricks by position.
TEST(BrickmapBounds, ConcurrentGrowthFromManyThreads) {
    brickmap<> m(box3i{{0, 0, 0}, {32, 32, 32}}, {4, 1});
    constexpr int threads = 4, per_thread = 12;
    std::vector<regions::sphere> spheres;
    for (int t = 0; t < threads; ++t)
        for (int i = 0; i < per_thread; ++i) {
            int d = 40 + 37 * i;
            glm::ivec3 dir = t == 0 ? glm::ivec3(-1, 0, 0) : t == 1 ? glm::ivec3(0, 1, 0)
                           : t == 2 ? glm::ivec3(0, 0, -1) : glm::ivec3(1, -1, 1);
            spheres.push_back({glm::ivec3(16) + dir * d, 3 + i % 5});
        }
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
            for (int i = 0; i < per_thread; ++i) {
                const auto& s = spheres[std::size_t(t * per_thread + i)];
                if (i % 3 == 0) m.set(s.centre + glm::ivec3(0, s.radius + 1, 0), 200);
                m.fill_sphere(s.centre, s.radius, std::uint8_t(1 + t), 1 + unsigned(i % 2));
            }
        });
    for (auto& p : pool) p.join();
    std::uint64_t expected = 0;
    for (int t = 0; t < threads; ++t)
        for (int i = 0; i < per_thread; ++i) {
            const auto& s = spheres[std::size_t(t * per_thread + i)];
            expected += sphere_voxels(s) + (i % 3 == 0);
            EXPECT_EQ(solid_in(m, s.bounds()), sphere_voxels(s)) << "thread " << t << " sphere " << i;
            EXPECT_EQ(m.get(s.centre), 1 + t);
        }
    EXPECT_EQ(m.voxel_count(), expected);
}
