// NAADF's host side: the layout's constants, the builder's cells (every empty cell's
// cuboid really is empty, uniform cells collapse, groups are shared), the group table's
// probing under hash collisions, sparse worlds, and determinism. Traversal on every
// backend is the conformance suite's job; here only what it cannot see.
#include <gtest/gtest.h>

#include <vector>

#include "naadf_cells.hpp"
#include "random_models.hpp"
#include "voxray/cpu.hpp"
#include "voxray/naadf/naadf.hpp"
#include "voxray/tracer.hpp"

namespace voxray::test {
namespace {

TEST(naadf_layout, cells_and_indices_round_trip) {
    EXPECT_EQ(VX_NA_STATE(0u), VX_NA_EMPTY);  // all-zero memory is empty space with AADF 0
    EXPECT_EQ(VX_NA_STATE(VX_NA_UNIFORM_CELL(0x7FFFu)), VX_NA_UNIFORM);
    EXPECT_EQ(VX_NA_PAYLOAD(VX_NA_MIXED_CELL(VX_NA_MAX_INDEX)), VX_NA_MAX_INDEX);
    EXPECT_EQ(VX_NA_STATE(VX_NA_MIXED_CELL(VX_NA_MAX_INDEX)), VX_NA_MIXED);
    // Six fields of 5 bits fit under the state bits; of 2 bits, under a voxel's solid bit.
    std::uint32_t page_fields = 0, voxel_fields = 0;
    for (unsigned dir = 0; dir < 6; ++dir) {
        page_fields |= VX_NA_AADF_PUT(31u, dir, 5u);
        voxel_fields |= VX_NA_AADF_PUT(3u, dir, 2u);
        EXPECT_EQ(VX_NA_AADF_FIELD(VX_NA_AADF_PUT(17u, dir, 5u), dir, 5u), 17u);
    }
    EXPECT_EQ(VX_NA_STATE(page_fields), VX_NA_EMPTY);
    EXPECT_EQ(voxel_fields & VX_NA_VOXEL_SOLID, 0u);
    // Every voxel of a page has its own (chunk, block, voxel) index triple.
    std::vector<bool> seen(1 << 24, false);
    for (unsigned z = 0; z < 256; z += 3)
        for (unsigned y = 0; y < 256; y += 5)
            for (unsigned x = 0; x < 256; ++x) {
                unsigned key = VX_NA_CHUNK_INDEX(x, y, z) << 12 | VX_NA_BLOCK_INDEX(x, y, z) << 6 | VX_NA_VOXEL_INDEX(x, y, z);
                ASSERT_FALSE(seen[key]) << x << " " << y << " " << z;
                seen[key] = true;
            }
    EXPECT_EQ(VX_NA_VOXEL_WORD(63u), VX_NA_GROUP_WORDS - 1u);
}

TEST(naadf_build, every_cell_matches_the_model_and_every_cuboid_is_empty) {
    // Straddles page, chunk and block boundaries, at negative coordinates too.
    voxel_model m = random_sparse(box3i{{-21, 240, -3}, {27, 275, 33}}, 400, 5);
    naadf s(m);
    expect_cells_match(s.blob(), m, s.bounds(), "build");
}

TEST(naadf_build, distance_fields_reach_the_edges_of_their_cell) {
    // One voxel: its block's other voxels reach the block's faces; the other blocks of its
    // chunk reach the chunk's faces; the page's other chunks reach the page's.
    voxel_model m;
    m.set({5, 6, 7}, 9);
    naadf s(m);
    auto w = s.blob();
    box3i voxel_cuboid = cuboid_of(w, {4, 6, 7}, cell_at(w, {4, 6, 7}));  // same block, -x neighbour
    EXPECT_EQ(voxel_cuboid.min.x, 4);
    EXPECT_EQ(voxel_cuboid.max.x, 5);
    decoded_cell block = cell_at(w, {1, 1, 1});
    EXPECT_EQ(block.level, 2);
    box3i block_cuboid = cuboid_of(w, {1, 1, 1}, block);
    EXPECT_EQ(block_cuboid.min, glm::ivec3(0));
    EXPECT_EQ(block_cuboid.max.x, 16);  // blocks x in [0, 4): all empty but the voxel's
    decoded_cell chunk = cell_at(w, {100, 100, 100});
    EXPECT_EQ(chunk.level, 4);
    EXPECT_EQ(cuboid_of(w, {100, 100, 100}, chunk).max, glm::ivec3(256));
}

TEST(naadf_build, uniform_cells_collapse_and_groups_are_shared) {
    voxel_model m;
    for (int z = 0; z < 32; ++z)
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) m.set({x, y, z}, 3);                 // 8 uniform chunks
    for (int z = 64; z < 96; ++z)
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x) m.set({x, y, z}, (x + y + z) % 2 ? 4 : 0);  // one checker pattern
    naadf s(m);
    EXPECT_EQ(s.stats().uniform_chunks, 8u);
    EXPECT_EQ(s.stats().mixed_chunks, 8u);
    EXPECT_EQ(s.stats().mixed_blocks, 8u * 64u);
    EXPECT_EQ(s.stats().groups, 1u);  // blocks start at multiples of 4: one checker phase
    EXPECT_TRUE(cell_at(s.blob(), {3, 3, 3}).solid);
    EXPECT_EQ(cell_at(s.blob(), {3, 3, 3}).level, 4);
}

TEST(naadf_build, a_sparse_16384_world_costs_megabytes) {
    voxel_model m;
    m.set({0, 0, 0}, 1);
    m.set({16383, 16383, 16383}, 2);
    naadf s(m);
    EXPECT_EQ(s.stats().pages, 64u * 64u * 64u);
    EXPECT_LT(s.bytes(), std::size_t(2) << 20);
    tracer<cpu, naadf> t(s);
    std::vector<ray> rays{ray{{-5.5f, 0.5f, 0.5f}, 0.0f, {1, 0, 0}}, ray{{16383.5f, 16383.5f, -1000.f}, 0.0f, {0, 0, 1}},
                          ray{{-1.f, -1.f, -1.f}, 0.0f, {1, 1, 1}}};
    std::vector<hit> hits(rays.size());
    t.closest_hit(rays, hits);
    EXPECT_EQ(hits[0].voxel, glm::ivec3(0, 0, 0));
    EXPECT_EQ(hits[1].voxel, glm::ivec3(16383));
    EXPECT_EQ(hits[1].material, 2u);
    EXPECT_EQ(hits[2].voxel, glm::ivec3(0, 0, 0));
    EXPECT_LT(hits[1].steps, 40u);  // empty pages, chunks and blocks in cuboid-sized moves
}

TEST(naadf_build, same_model_same_bytes_whatever_the_threads) {
    voxel_model m = random_model(70, 0.05f, 3, {-30, 10, 200});
    naadf one(m, {.threads = 1}), two(m, {.threads = 2});
    auto a = one.blob(), b = two.blob();
    ASSERT_EQ(a.size(), b.size());
    EXPECT_TRUE(std::equal(a.begin(), a.end(), b.begin()));
}

TEST(naadf_build, without_distance_fields_the_hits_are_the_same_and_the_walks_longer) {
    voxel_model m = random_model(48, 0.02f, 8);
    naadf fields(m), bare(m, {.distance_fields = false});
    auto rays = random_rays(m.bounds(), 4000, 12);
    std::vector<hit> a(rays.size()), b(rays.size());
    tracer<cpu, naadf>(fields).closest_hit(rays, a);
    tracer<cpu, naadf>(bare).closest_hit(rays, b);
    std::uint64_t steps_a = 0, steps_b = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        ASSERT_EQ(a[i].status, b[i].status) << i;
        ASSERT_EQ(a[i].voxel, b[i].voxel) << i;
        ASSERT_EQ(a[i].t, b[i].t) << i;
        ASSERT_EQ(a[i].normal, b[i].normal) << i;
        ASSERT_EQ(a[i].material, b[i].material) << i;
        steps_a += a[i].steps, steps_b += b[i].steps;
    }
    EXPECT_LT(2 * steps_a, steps_b);
}

TEST(naadf_aadf, the_unrolled_4x4x4_growth_matches_the_generic_one) {
    rng g(21);
    for (int n = 0; n < 3000; ++n) {
        // Densities from sparse to nearly full, so every face and limit gets hit.
        std::uint64_t solid = 0;
        double density = (n % 10) / 10.0;
        for (int i = 0; i < 64; ++i) solid |= std::uint64_t(g.uniform() < density) << i;
        std::vector<std::uint8_t> cells(64);
        for (int i = 0; i < 64; ++i) cells[i] = (solid >> i) & 1u;  // x fastest = the 4^3 index
        auto unrolled = naadf_detail::grid4_aadfs(solid, 2);
        auto generic = naadf_detail::grid_aadfs(glm::ivec3(4), cells, 3, 2);
        for (int i = 0; i < 64; ++i) ASSERT_EQ(unrolled[i], generic[i]) << "mask " << solid << " cell " << i;
    }
}

TEST(naadf_groups, probing_under_hash_collisions_never_returns_another_group) {
    // H = c0 + sum 31^(64-i) v_i: voxel i one lower and voxel i+1 31 higher collide.
    naadf_detail::voxel_group a{}, b{};
    auto put = [](naadf_detail::voxel_group& g, int i, std::uint32_t v) { g[VX_NA_VOXEL_WORD(i)] |= v << VX_NA_VOXEL_SHIFT(i); };
    put(a, 0, VX_NA_SOLID_VOXEL(40u)), put(a, 1, VX_NA_SOLID_VOXEL(7u));
    put(b, 0, VX_NA_SOLID_VOXEL(39u)), put(b, 1, VX_NA_SOLID_VOXEL(38u));
    ASSERT_EQ(naadf_detail::group_hash(a), naadf_detail::group_hash(b));
    naadf_detail::group_table table;
    std::uint32_t ia = table.intern(a), ib = table.intern(b);
    EXPECT_NE(ia, ib);
    // Thousands more, through several growths of the table: each keeps its own index.
    std::vector<naadf_detail::voxel_group> many;
    for (std::uint32_t n = 0; n < 5000; ++n) {
        naadf_detail::voxel_group g{};
        put(g, int(n % 63), VX_NA_SOLID_VOXEL(n % 1000 + 1)), put(g, 63, VX_NA_SOLID_VOXEL(n / 63 + 1));
        many.push_back(g);
    }
    std::vector<std::uint32_t> index;
    for (auto& g : many) index.push_back(table.intern(g));
    EXPECT_EQ(table.intern(a), ia);
    EXPECT_EQ(table.intern(b), ib);
    for (std::size_t n = 0; n < many.size(); ++n) {
        ASSERT_EQ(table.intern(many[n]), index[n]);
        ASSERT_EQ(table.group(index[n]), many[n]);
    }
}

}  // namespace
}  // namespace voxray::test
