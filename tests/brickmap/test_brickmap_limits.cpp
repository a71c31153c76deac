// The blob limit: growth fills the pool up to it (not doubling past it, which wasted up
// to half of the documented 8 GiB), and an edit that hits it fails with a clear error
// and leaves the map consistent: its count matches its content and it saves and loads.
// A small configured limit (options::max_blob_bytes) stands in for 8 GiB.
#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "voxray/brickmap/brickmap.hpp"
#include "voxray/brickmap/serialize.hpp"

using namespace voxray;

namespace {

template <class Map>
std::uint64_t count_solid(const Map& m) {
    std::uint64_t n = 0;
    box3i b = m.bounds();
    for (int z = b.min.z; z < b.max.z; ++z)
        for (int y = b.min.y; y < b.max.y; ++y)
            for (int x = b.min.x; x < b.max.x; ++x) n += m.get({x, y, z}) != 0;
    return n;
}

constexpr std::uint64_t brick_bytes = brickmap<>::codec::words * 4;

}  // namespace

TEST(BrickmapLimits, PoolGrowsUpToTheLimitNotHalfOfIt) {
    constexpr std::uint64_t limit = 1 << 20;
    brickmap<> m(box3i{{0, 0, 0}, {128, 128, 128}}, {.max_blob_bytes = limit});  // one page, 4096 bricks
    std::uint64_t placed = 0;
    std::string what;
    try {
        for (int z = 0; z < 128; z += 8)
            for (int y = 0; y < 128; y += 8)
                for (int x = 0; x < 128; x += 8, ++placed) m.set({x, y, z}, 1);
    } catch (const error& e) {
        what = e.what();
    }
    EXPECT_NE(what.find("limit of 1048576 bytes"), std::string::npos) << what;
    EXPECT_LE(m.bytes(), limit);
    EXPECT_GT(m.bytes() + brick_bytes, limit) << "the pool stopped short of the limit";
    EXPECT_EQ(m.brick_count(), placed);
    EXPECT_EQ(m.voxel_count(), placed);
}

TEST(BrickmapLimits, FailedRegionEditLeavesCountMatchingContent) {
    for (unsigned threads : {1u, 3u}) {
        brickmap<> m(box3i{{0, 0, 0}, {128, 128, 128}}, {.max_blob_bytes = 160 << 10});
        m.fill_box({{0, 0, 0}, {20, 3, 20}}, 2);
        // A sphere's surface needs ~700 partial bricks: far above the limit.
        EXPECT_THROW(m.fill_sphere({64, 64, 64}, 60, 5, threads), error);
        EXPECT_EQ(m.voxel_count(), count_solid(m)) << threads << " threads";
        auto path = std::filesystem::temp_directory_path() /
                    ("voxray_limits_" + std::to_string(::getpid()) + "_" + std::to_string(threads) + ".vxbm");
        save(m, path);
        auto back = load_brickmap<brickmap<>>(path);  // throws if count and content disagree
        EXPECT_EQ(back.voxel_count(), m.voxel_count());
        std::filesystem::remove(path);
        // Still usable: an edit that fits goes through.
        m.erase_sphere({64, 64, 64}, 70);
        m.fill_sphere({10, 10, 10}, 4, 7);
        EXPECT_EQ(m.voxel_count(), count_solid(m));
        EXPECT_EQ(m.get({10, 14, 10}), 7);
    }
}

// reserve() re-lays the blob out once, ahead: the bricks that follow are sent one by one,
// not as whole-blob uploads after each doubling.
TEST(BrickmapLimits, ReserveMakesRoomAheadSoLaterBricksAreIncremental) {
    brickmap<> m(box3i{{0, 0, 0}, {128, 128, 128}}, {.initial_bricks = 4});
    (void)m.take_dirty_ranges();
    m.reserve(600);
    EXPECT_GE(m.brick_capacity(), 600u);
    auto after_reserve = m.take_dirty_ranges();
    ASSERT_EQ(after_reserve.size(), 1u);  // the re-layout itself: the whole blob, once
    EXPECT_EQ(after_reserve[0].count, m.blob().size());
    std::size_t words = m.blob().size();
    for (int i = 0; i < 500; ++i) {
        m.set({8 * (i % 16), 8 * (i / 16 % 16), 8 * (i / 256)}, 3);
        auto ranges = m.take_dirty_ranges();
        std::uint64_t sent = 0;
        for (auto& r : ranges) sent += r.count;
        ASSERT_LE(sent, 2u * brickmap<>::codec::words) << "brick " << i;
    }
    EXPECT_EQ(m.blob().size(), words);
    EXPECT_EQ(m.brick_count(), 500u);
}
