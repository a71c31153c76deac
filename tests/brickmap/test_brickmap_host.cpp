// Host-side brickmap: build from models, collapse, pool growth and recycling, region
// edits and concurrent edits against a dense reference, dirty ranges, files.
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "random_models.hpp"
#include "test_data.hpp"
#include "voxray/brickmap/brickmap.hpp"
#include "voxray/brickmap/serialize.hpp"
#include "voxray/io/vox_reader.hpp"

using namespace voxray;

namespace {

// Every voxel of the model's bounds (and a margin) agrees; nothing else is solid.
template <class Map>
void expect_matches(const Map& m, const voxel_model& model) {
    ASSERT_EQ(m.voxel_count(), model.voxel_count());
    box3i b = model.bounds();
    std::uint64_t mismatches = 0;
    for (int z = b.min.z - 1; z <= b.max.z; ++z)
        for (int y = b.min.y - 1; y <= b.max.y; ++y)
            for (int x = b.min.x - 1; x <= b.max.x; ++x)
                if (std::uint32_t(m.get({x, y, z})) != model.get({x, y, z}) && ++mismatches < 5)
                    ADD_FAILURE() << "voxel " << x << "," << y << "," << z << ": " << std::uint32_t(m.get({x, y, z}))
                                  << " vs " << int(model.get({x, y, z}));
    EXPECT_EQ(mismatches, 0u);
}

// A dense reference world for edit tests.
template <class Payload>
struct reference {
    box3i world;
    std::vector<Payload> v;
    explicit reference(box3i w) : world(w), v(w.volume(), 0) {}
    Payload& at(glm::ivec3 p) {
        glm::ivec3 q = p - world.min, e = world.extent();
        return v[(std::size_t(q.z) * e.y + q.y) * e.x + q.x];
    }
    template <class Region>
    void apply(const Region& r, edit_op op, Payload value) {
        box3i b = r.bounds();
        for (int z = std::max(b.min.z, world.min.z); z < std::min(b.max.z, world.max.z); ++z)
            for (int y = std::max(b.min.y, world.min.y); y < std::min(b.max.y, world.max.y); ++y)
                for (int x = std::max(b.min.x, world.min.x); x < std::min(b.max.x, world.max.x); ++x)
                    if (r.contains({x, y, z})) edit(at({x, y, z}), op, value);
    }
    static void edit(Payload& p, edit_op op, Payload value) {
        if (op == edit_op::fill) p = value;
        else if (op == edit_op::erase) p = 0;
        else if (p) p = value;
    }
    template <class Map>
    void expect_equal(const Map& m) {
        std::uint64_t bad = 0, count = 0;
        glm::ivec3 e = world.extent();
        for (int z = 0; z < e.z; ++z)
            for (int y = 0; y < e.y; ++y)
                for (int x = 0; x < e.x; ++x) {
                    glm::ivec3 p = world.min + glm::ivec3(x, y, z);
                    Payload want = at(p);
                    count += want != 0;
                    if (m.get(p) != want && ++bad < 5)
                        ADD_FAILURE() << "voxel " << p.x << "," << p.y << "," << p.z << ": " << std::uint64_t(m.get(p))
                                      << " vs " << std::uint64_t(want);
                }
        EXPECT_EQ(bad, 0u);
        EXPECT_EQ(m.voxel_count(), count);
    }
};

template <class Map>
void expect_pool_consistent(const Map& m) {
    EXPECT_EQ(m.brick_count() + m.free_bricks(), m.bricks_used());
    EXPECT_LE(m.bricks_used(), m.brick_capacity());
}

}  // namespace

TEST(BrickmapBuild, RandomModelsAllPayloadsAndEdges) {
    auto model = test::random_model(40, 0.3f, 11, {-13, 5, 7});
    auto a = brickmap<std::uint8_t, 8>::build(model, 2);
    expect_matches(a, model);
    expect_pool_consistent(a);
    auto b = brickmap<std::uint16_t, 4>::build(model, 1);
    expect_matches(b, model);
    auto c = brickmap<std::uint32_t, 16>::build(model, 2);
    expect_matches(c, model);
    auto d = brickmap<std::uint8_t, 8>::build(test::hollow_box(37, {3, -20, 1}), 2);
    expect_matches(d, test::hollow_box(37, {3, -20, 1}));
}

TEST(BrickmapBuild, SharedVoxFiles) {
    VOXRAY_REQUIRE_DATA();
    int tested = 0;
    for (auto& file : test::data_files("vox", ".vox")) {
        if (std::filesystem::file_size(file) > (4u << 20)) continue;  // keep the dense comparison short
        SCOPED_TRACE(file.string());
        auto model = io::load_vox(file);
        auto m = brickmap<>::build(model, 2);
        expect_matches(m, model);
        if (++tested == 4) break;
    }
    EXPECT_GT(tested, 0);
}

TEST(BrickmapBuild, UniformBricksCollapse) {
    auto model = test::solid_block({0, 0, 0}, {32, 32, 32}, 9);
    auto m = brickmap<>::build(model, 2);
    EXPECT_EQ(m.brick_count(), 0u);
    EXPECT_EQ(m.voxel_count(), 32u * 32 * 32);
    expect_matches(m, model);

    brickmap<std::uint32_t> big(box3i{{0, 0, 0}, {64, 64, 64}});
    big.fill_box({{8, 8, 8}, {40, 40, 40}}, 5);
    EXPECT_EQ(big.brick_count(), 0u);
    big.fill_box({{16, 16, 16}, {24, 24, 24}}, 0x80000001u);  // too wide for a solid cell
    EXPECT_EQ(big.brick_count(), 1u);
    EXPECT_EQ(big.get({20, 20, 20}), 0x80000001u);
    big.set({9, 9, 9}, 6);  // expands a solid cell
    EXPECT_EQ(big.brick_count(), 2u);
    big.set({9, 9, 9}, 5);
    big.settle();  // collapses again
    EXPECT_EQ(big.brick_count(), 1u);
}

TEST(BrickmapPool, GrowsFromTinyCapacityAndRecycles) {
    box3i world{{-50, -50, -50}, {78, 78, 78}};
    brickmap<> m(world, {1, 1});
    reference<std::uint8_t> ref(world);
    std::mt19937 g(3);
    for (int i = 0; i < 3000; ++i) {
        glm::ivec3 p{int(g() % 128) - 50, int(g() % 128) - 50, int(g() % 128) - 50};
        auto v = std::uint8_t(1 + g() % 200);
        m.set(p, v);
        ref.at(p) = v;
    }
    EXPECT_GT(m.brick_capacity(), 1000u);
    ref.expect_equal(m);
    std::uint32_t cap = m.brick_capacity(), used = m.bricks_used();
    m.erase_box(world, 2);
    EXPECT_EQ(m.voxel_count(), 0u);
    EXPECT_EQ(m.brick_count(), 0u);
    EXPECT_EQ(m.free_bricks(), used);
    m.apply(regions::sphere{{10, 10, 10}, 30}, edit_op::fill, 3, 2);
    m.apply(regions::sphere{{10, 10, 10}, 28}, edit_op::erase, 0, 2);  // a shell: many bricks
    EXPECT_EQ(m.brick_capacity(), cap);
    EXPECT_EQ(m.bricks_used(), used);  // all came from the ring
    expect_pool_consistent(m);
}

TEST(BrickmapEdit, RegionsMatchReference) {
    box3i world{{-7, 3, -20}, {90, 70, 51}};
    // Regions reach outside the world: clipped here, like the reference (growth has its
    // own tests in test_brickmap_bounds.cpp).
    brickmap<std::uint16_t, 8> m(world, {.outside = outside_edits::clip});
    reference<std::uint16_t> ref(world);
    std::mt19937 g(42);
    auto rnd = [&](int lo, int hi) { return lo + int(g() % unsigned(hi - lo)); };
    auto point = [&] { return glm::ivec3(rnd(-15, 98), rnd(-5, 78), rnd(-28, 59)); };
    for (int i = 0; i < 400; ++i) {
        auto op = edit_op(g() % 3);
        auto v = std::uint16_t(1 + g() % 1000);
        int kind = int(g() % 5);
        unsigned threads = 1 + g() % 2;
        if (kind == 0) {
            glm::ivec3 a = point(), b = a + glm::ivec3(rnd(1, 30), rnd(1, 30), rnd(1, 30));
            regions::box r{{a, b}};
            m.apply(r, op, v, threads);
            ref.apply(r, op, v);
        } else if (kind == 1) {
            regions::sphere r{point(), rnd(0, 20)};
            m.apply(r, op, v, threads);
            ref.apply(r, op, v);
        } else if (kind == 2) {
            regions::capsule r{point(), point(), rnd(1, 5)};
            m.apply(r, op, v, threads);
            ref.apply(r, op, v);
        } else if (kind == 3) {
            glm::ivec3 a = point(), b = point();
            m.apply_line(a, b, 0, op, v);
            regions::line_voxels(a, b, [&](glm::ivec3 p) {
                if (world.contains(p)) reference<std::uint16_t>::edit(ref.at(p), op, v);
            });
        } else {
            glm::ivec3 a = point();
            box3i src{a, a + glm::ivec3(rnd(1, 20), rnd(1, 20), rnd(1, 20))};
            glm::ivec3 off(rnd(-10, 10), rnd(-10, 10), rnd(-10, 10));
            bool replace = g() % 2;
            m.copy_region(src, off, op, replace);
            box3i s{glm::max(src.min, world.min), glm::min(src.max, world.max)};
            if (s.empty()) continue;
            std::vector<std::pair<glm::ivec3, std::uint16_t>> vals;
            for (int z = s.min.z; z < s.max.z; ++z)
                for (int y = s.min.y; y < s.max.y; ++y)
                    for (int x = s.min.x; x < s.max.x; ++x) vals.push_back({{x, y, z}, ref.at({x, y, z})});
            for (auto [p, sv] : vals) {
                glm::ivec3 d = p + off;
                if (!world.contains(d)) continue;
                if (replace) ref.at(d) = sv;
                else if (sv) reference<std::uint16_t>::edit(ref.at(d), op, op == edit_op::erase ? 0 : sv);
            }
        }
    }
    ref.expect_equal(m);
    expect_pool_consistent(m);
}

TEST(BrickmapEdit, BatchMatchesSequentialReference) {
    box3i world{{0, 0, 0}, {160, 96, 120}};
    brickmap<> m(world, {8, 1, outside_edits::clip});  // the reference clips too
    reference<std::uint8_t> ref(world);
    std::mt19937 g(9);
    for (int round = 0; round < 10; ++round) {
        std::vector<brickmap<>::edit> edits;
        for (int i = 0; i < 60; ++i) {
            glm::ivec3 c(int(g() % 160), int(g() % 96), int(g() % 120));
            auto op = edit_op(g() % 3);
            auto v = std::uint8_t(g() % 4 == 0 ? 0 : 1 + g() % 255);
            int kind = int(g() % 3);
            if (kind == 0) edits.push_back({regions::sphere{c, int(g() % 20)}, op, v});
            else if (kind == 1) edits.push_back({regions::box{{c - 5, c + int(1 + g() % 25)}}, op, v});
            else edits.push_back({regions::capsule{c, c + glm::ivec3(int(g() % 30) - 15, 9, 3), 2}, op, v});
        }
        m.apply_batch(edits, 2);
        for (auto& e : edits)
            std::visit([&](const auto& r) { ref.apply(r, e.value ? e.op : edit_op::erase, e.value); }, e.region);
    }
    ref.expect_equal(m);
    expect_pool_consistent(m);
}

TEST(BrickmapEdit, ConcurrentDisjointAndOverlapping) {
    box3i world{{0, 0, 0}, {128, 96, 80}};
    brickmap<> m(world, {4, 1, outside_edits::clip});  // the reference clips too
    reference<std::uint8_t> ref(world);
    constexpr int threads = 4;
    // Phase 1: each thread owns an x slab (boundaries inside bricks, so threads share
    // bricks) and applies random edits there; the reference slab is its own.
    {
        std::vector<std::thread> pool;
        for (int t = 0; t < threads; ++t)
            pool.emplace_back([&, t] {
                std::mt19937 g(100 + t);
                int x0 = t * 32 + 3, x1 = t * 32 + 32 + 3;
                if (t == threads - 1) x1 = 128;
                auto clip = [&](box3i b) { b.min.x = std::max(b.min.x, x0); b.max.x = std::min(b.max.x, x1); return b; };
                for (int i = 0; i < 800; ++i) {
                    auto op = edit_op(g() % 3);
                    auto v = std::uint8_t(1 + g() % 250);
                    glm::ivec3 a(x0 + int(g() % unsigned(x1 - x0)), int(g() % 96), int(g() % 80));
                    if (g() % 4 == 0) {  // single voxels
                        m.set(a, op == edit_op::erase ? 0 : v);
                        ref.at(a) = op == edit_op::erase ? 0 : v;
                        continue;
                    }
                    regions::box r{clip({a - int(g() % 9), a + 1 + int(g() % 12)})};
                    m.apply(r, op, v);
                    ref.apply(r, op, v);
                }
            });
        for (auto& p : pool) p.join();
    }
    ref.expect_equal(m);
    // Phase 2: overlapping spheres, every thread fills the same value, then paints
    // another, then erases overlapping boxes: the result does not depend on the order.
    std::vector<regions::sphere> spheres;
    std::vector<regions::box> boxes;
    std::mt19937 g(7);
    for (int i = 0; i < 400; ++i) spheres.push_back({{int(g() % 128), int(g() % 96), int(g() % 80)}, int(g() % 14)});
    for (int i = 0; i < 200; ++i) {
        glm::ivec3 a(int(g() % 128), int(g() % 96), int(g() % 80));
        boxes.push_back({{a, a + glm::ivec3(1 + g() % 20, 1 + g() % 20, 1 + g() % 20)}});
    }
    auto parallel = [&](auto&& body) {
        std::vector<std::thread> pool;
        for (int t = 0; t < threads; ++t) pool.emplace_back([&, t] { body(t); });
        for (auto& p : pool) p.join();
    };
    parallel([&](int t) {
        for (std::size_t i = t; i < spheres.size(); i += 2) m.apply(spheres[i % spheres.size()], edit_op::fill, 77);
    });
    for (auto& s : spheres) ref.apply(s, edit_op::fill, 77);
    parallel([&](int t) {
        for (std::size_t i = t; i < boxes.size(); i += 3) m.apply(boxes[i], edit_op::paint, 99);
        for (int i = 0; i < 2000; ++i) m.set({(t * 37 + i * 5) % 128, (i * 7) % 96, (i * 3) % 80}, 99);
    });
    for (auto& bx : boxes) ref.apply(bx, edit_op::paint, 99);  // t = 0, 1, 2 cover every index
    for (int t = 0; t < threads; ++t)
        for (int i = 0; i < 2000; ++i) ref.at({(t * 37 + i * 5) % 128, (i * 7) % 96, (i * 3) % 80}) = 99;
    parallel([&](int t) {
        for (std::size_t i = t; i < boxes.size(); i += 5) m.apply(boxes[i], edit_op::erase, 0, 2);
    });
    for (std::size_t i = 0; i < boxes.size(); ++i)
        if (i % 5 != 4) ref.apply(boxes[i], edit_op::erase, 0);
    m.settle();
    ref.expect_equal(m);
    expect_pool_consistent(m);
}

TEST(BrickmapEdit, ConcurrentSetOfOneNewCellAllocatesOneBrick) {
    brickmap<> m(box3i{{0, 0, 0}, {256, 256, 256}}, {1, 1});
    m.set({255, 255, 255}, 1);  // one page, so contention is on the cells only
    constexpr int threads = 8, cells = 200;
    std::atomic<int> go{0};
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([&, t] {
            go.fetch_add(1);
            while (go.load() < threads) {}
            for (int c = 0; c < cells; ++c) {
                glm::ivec3 base(8 * (c % 16), 8 * (c / 16), 8 * (c % 7));
                m.set(base + glm::ivec3(t % 8, t / 8, 3), std::uint8_t(1 + t));
            }
        });
    for (auto& p : pool) p.join();
    EXPECT_EQ(m.brick_count(), std::uint64_t(cells) + 1);
    EXPECT_EQ(m.voxel_count(), std::uint64_t(cells) * threads + 1);
    expect_pool_consistent(m);
}

TEST(BrickmapDirty, OneVoxelEditInA4096World) {
    brickmap<> m(box3i{{0, 0, 0}, {4096, 4096, 4096}}, {1024, 16});  // no growth below
    m.fill_sphere({2000, 2000, 2000}, 30, 5);
    auto first = m.take_dirty_ranges();
    ASSERT_EQ(first.size(), 1u);  // new map: whole blob
    EXPECT_EQ(first[0].count, m.blob().size());
    std::printf("4096^3 world, one r=30 ball: %zu blob bytes, %llu bricks\n", m.bytes(),
                (unsigned long long)m.brick_count());
    auto total = [](const std::vector<word_range>& r) {
        std::uint64_t n = 0;
        for (auto& x : r) n += x.count;
        return n;
    };
    m.set({2000, 2000, 2031}, 9);  // existing brick at the sphere's edge
    auto r1 = m.take_dirty_ranges();
    EXPECT_LE(total(r1), 150u);
    EXPECT_GE(total(r1), 1u);
    m.set({2000, 2000, 2000}, 5);  // same value: nothing
    EXPECT_TRUE(m.take_dirty_ranges().empty());
    m.set({2100, 2000, 2000}, 9);  // a new brick in an existing page
    auto r2 = m.take_dirty_ranges();
    EXPECT_LE(total(r2), 160u);
    for (auto& r : r2) EXPECT_LE(r.offset + r.count, m.blob().size());
    m.set({2100, 2000, 2000}, 0);  // erase: the brick is recycled, its cell word changes
    auto r3 = m.take_dirty_ranges();
    EXPECT_LE(total(r3), 150u);
    EXPECT_EQ(m.get({2100, 2000, 2000}), 0);
    std::printf("dirty words: edit %llu, new brick %llu, recycle %llu\n", (unsigned long long)total(r1),
                (unsigned long long)total(r2), (unsigned long long)total(r3));
}

namespace {
std::filesystem::path temp_file(const char* name) {
    return std::filesystem::temp_directory_path() / (std::string("voxray_bm_") + std::to_string(getpid()) + name);
}
std::vector<char> read_all(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}
void write_all(const std::filesystem::path& p, const std::vector<char>& b, std::size_t n) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(b.data(), std::streamsize(n));
}
}  // namespace

TEST(BrickmapSaveLoad, RoundTripAndCorruption) {
    using map = brickmap<std::uint8_t, 8>;
    auto model = test::random_model(24, 0.2f, 5, {-3, 0, 2});
    auto m = map::build(model, 2);
    m.fill_box({{-3, 0, 2}, {5, 8, 10}}, 3);
    m.set({0, 0, 2}, 0);
    auto path = temp_file("a.vxbm"), bad = temp_file("b.vxbm");
    save(m, path);
    auto loaded = load_brickmap<map>(path);
    ASSERT_EQ(loaded.blob().size(), m.blob().size());
    EXPECT_TRUE(std::equal(m.blob().begin(), m.blob().end(), loaded.blob().begin()));
    EXPECT_EQ(loaded.voxel_count(), m.voxel_count());
    EXPECT_EQ(loaded.brick_count(), m.brick_count());
    loaded.set({0, 0, 3}, 0);  // the loaded map is editable
    loaded.fill_box({{0, 0, 0}, {24, 24, 24}}, 1);

    auto bytes = read_all(path);
    auto expect_error = [&](const std::vector<char>& b, std::size_t n, const char* what) {
        write_all(bad, b, n);
        try {
            (void)load_brickmap<map>(bad);
            ADD_FAILURE() << what << ": loaded without error";
        } catch (const voxray::error& e) {
            EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
        }
    };
    for (std::size_t i = 0; i < bytes.size(); i += (i < 256 ? 1 : 97)) {
        auto b = bytes;
        b[i] ^= 0x10;
        expect_error(b, b.size(), "flipped byte");
    }
    for (std::size_t n = 0; n < bytes.size(); n += (n < 100 ? 1 : 331)) expect_error(bytes, n, "truncated");
    auto b = bytes;
    std::uint64_t huge = std::uint64_t(1) << 40;
    std::memcpy(b.data() + 16, &huge, 8);
    expect_error(b, b.size(), "huge size");
    // Wrong payload type.
    using wide = brickmap<std::uint16_t, 8>;
    using small = brickmap<std::uint8_t, 4>;
    EXPECT_THROW((void)load_brickmap<wide>(path), voxray::error);
    EXPECT_THROW((void)load_brickmap<small>(path), voxray::error);
    // A content error behind a valid checksum: a brick index past the pool.
    b = bytes;
    std::uint32_t pages_off, words_count;
    std::memcpy(&pages_off, b.data() + 48 + 4 * VX_BM_HEADER_PAGES, 4);
    std::memcpy(&words_count, b.data() + 16, 4);
    std::size_t cell = 48 + 4 * std::size_t(pages_off);
    std::uint32_t evil = (100000u << 1) | 1u;
    std::memcpy(b.data() + cell, &evil, 4);
    fnv64 sum;
    sum.bytes(b.data(), 40);
    sum.words(reinterpret_cast<const std::uint32_t*>(b.data() + 48), words_count);
    sum.bytes(b.data() + 48 + 4 * std::size_t(words_count), b.size() - 48 - 4 * std::size_t(words_count));  // palette
    std::memcpy(b.data() + 40, &sum.h, 8);
    expect_error(b, b.size(), "bad brick index");
    std::filesystem::remove(path);
    std::filesystem::remove(bad);
}

TEST(BrickmapBuild, HugeWorldIsCheap) {
    brickmap<> m(box3i{{-8192, -8192, -8192}, {8192, 8192, 8192}});  // 16384^3 voxels
    EXPECT_LT(m.bytes(), 16u << 20);  // a 128^3-word page table plus one page and a few bricks
    m.set({8191, 8191, 8191}, 4);
    m.set({-8192, -8192, -8192}, 5);
    m.fill_sphere({0, 0, 0}, 20, 6);
    EXPECT_EQ(m.get({8191, 8191, 8191}), 4);
    EXPECT_EQ(m.get({-8192, -8192, -8192}), 5);
    EXPECT_EQ(m.get({0, 0, 20}), 6);
    EXPECT_EQ(m.get({0, 0, 21}), 0);
    brickmap<> fixed(m.bounds(), {.outside = outside_edits::fail});
    EXPECT_THROW(fixed.set({8192, 0, 0}, 1), voxray::error);
}
