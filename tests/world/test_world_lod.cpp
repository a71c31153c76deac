// The chunked world's LOD chain and its cuts. What a LOD n chunk holds is checked against
// the rule (Aokana 3.4: a voxel where at least `density` of its 8 children are, with
// their average colour or most frequent index); what rays see through any cut, on every
// backend, against the reference over the cut's voxels expanded to world voxels (a LOD n
// voxel is a 2^n cube): same voxel, t, face and material. At LOD 0 that is the model
// itself (also the conformance suite's check, for "world" and "world-16").
#include <gtest/gtest.h>

#include <map>
#include <string>

#include "random_models.hpp"
#include "special_rays.hpp"
#include "voxray/check/compare.hpp"
#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/scenes/builtin.hpp"
#include "voxray/svdag/decode.hpp"
#include "voxray/tracer.hpp"
#include "voxray/world/world.hpp"
#include "every_backend.hpp"
#include "world_test_model.hpp"

namespace voxray {
namespace {

using namespace voxray::test;

chunk_voxels voxels_of(std::initializer_list<std::pair<glm::ivec3, std::uint32_t>> list) {
    chunk_voxels v;
    for (auto& [p, value] : list) v.keys.push_back(chunk_voxels::key(p)), v.values.push_back(value);
    v.sort();
    return v;
}

TEST(world_lod, a_coarse_voxel_needs_density_children_and_takes_their_average_or_most_frequent_value) {
    // Chunk edge 16: child octant 1 (x = 1) covers parent x in [8, 16).
    chunk_voxels a = voxels_of({{{0, 0, 0}, 5}, {{1, 0, 0}, 7}, {{1, 1, 1}, 7},   // parent (0,0,0): 3 children
                                {{4, 4, 4}, 9},                                   // parent (2,2,2): 1 child
                                {{14, 15, 15}, 3}, {{15, 15, 15}, 3}});           // parent (7,7,7): 2
    chunk_voxels b = voxels_of({{{0, 0, 0}, 11}, {{1, 1, 0}, 11}});               // in octant 1: parent (8,0,0)
    std::array<const chunk_voxels*, 8> children{&a, &b, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr};

    chunk_voxels two = downsample(children, 4, 2, false);
    ASSERT_EQ(two.size(), 3u);
    EXPECT_EQ(two.keys[0], chunk_voxels::key({0, 0, 0}));
    EXPECT_EQ(two.values[0], 7u);  // 7 twice, 5 once
    EXPECT_EQ(two.keys[1], chunk_voxels::key({8, 0, 0}));
    EXPECT_EQ(two.keys[2], chunk_voxels::key({7, 7, 7}));
    EXPECT_EQ(downsample(children, 4, 1, false).size(), 4u);  // the lone voxel too
    EXPECT_EQ(downsample(children, 4, 3, false).size(), 1u);

    // Colours: the rounded per-channel average, alpha included.
    chunk_voxels c = voxels_of({{{0, 0, 0}, 0xFF000010u}, {{0, 1, 0}, 0xFF0000FFu}, {{1, 1, 1}, 0x80FF2000u}});
    chunk_voxels avg = downsample({&c, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr, nullptr}, 4, 2, true);
    ASSERT_EQ(avg.size(), 1u);
    std::uint32_t r = (0x10 + 0xFF + 0x00 + 1) / 3, g = (0 + 0 + 0x20 + 1) / 3, bl = (0 + 0 + 0xFF + 1) / 3,
                  al = (0xFF + 0xFF + 0x80 + 1) / 3;
    EXPECT_EQ(avg.values[0], r | g << 8 | bl << 16 | al << 24);
    EXPECT_THROW(downsample(children, 4, 0, false), error);
    EXPECT_THROW(downsample(children, 4, 9, false), error);
}

TEST(world_lod, chunk_dags_hold_their_voxels) {
    voxel_model model = random_model(40, 0.3f, 5);
    auto cells = cut_into_cells(model, glm::ivec3(0), 5, false);
    ASSERT_GT(cells.size(), 1u);
    for (auto& [cell, voxels] : cells) {
        chunk_record c = build_chunk(voxels, {0, cell}, 5, {});
        EXPECT_EQ(c.voxel_count, voxels.size());
        auto decoded = decode_svdag(c.dag);
        ASSERT_EQ(decoded.size(), voxels.size());
        chunk_voxels back;
        for (auto& d : decoded) back.keys.push_back(chunk_voxels::key(d.position)), back.values.push_back(d.attribute);
        back.sort();
        EXPECT_EQ(back.keys, voxels.keys);
        EXPECT_EQ(back.values, voxels.values);
        for (auto& d : decoded) {
            EXPECT_TRUE(glm::all(glm::greaterThanEqual(d.position, c.solid_min)));
            EXPECT_TRUE(glm::all(glm::lessThanEqual(d.position, c.solid_max)));
        }
    }
    EXPECT_THROW(build_chunk({}, {}, 3, {}), error);
    EXPECT_THROW(build_chunk({}, {}, 11, {}), error);
}

// The reference for a cut: every cell gets the voxels of the chunk standing for it (the
// finest placement covering it), each DAG voxel of a LOD n chunk a 2^n cube.
voxel_model expand(const chunked_world& w, std::vector<placement> cut) {
    const world_grid& g = w.grid();
    std::stable_sort(cut.begin(), cut.end(), [](auto& a, auto& b) { return a.key.lod > b.key.lod; });
    std::map<glm::ivec3, placement, ivec3_less> standing;
    for (auto& p : cut) {
        glm::ivec3 lo = p.key.cell << p.key.lod;
        int n = 1 << p.key.lod;
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) standing[lo + glm::ivec3(x, y, z)] = p;
    }
    voxel_model out;
    std::map<const chunk_record*, std::vector<decoded_voxel>> decoded;
    for (auto& [cell, p] : standing) {
        if (!p.chunk || p.chunk->empty()) continue;
        auto& voxels = decoded.try_emplace(p.chunk, decode_svdag(p.chunk->dag)).first->second;
        int lod = p.key.lod, size = 1 << lod;
        glm::ivec3 chunk_base = (p.key.cell << lod) << g.chunk_bits;
        box3i cell_box{cell << g.chunk_bits, (cell + 1) << g.chunk_bits};
        for (auto& v : voxels) {
            glm::ivec3 lo = chunk_base + (v.position << lod);
            if (!cell_box.contains(lo)) continue;  // a coarse voxel lies in one cell (size <= C)
            for (int z = 0; z < size; ++z)
                for (int y = 0; y < size; ++y)
                    for (int x = 0; x < size; ++x) out.set(g.origin + lo + glm::ivec3(x, y, z), std::uint8_t(v.attribute));
        }
    }
    return out;
}

template <class Backend>
void cut_matches_its_reference(const chunked_world& w, const std::vector<placement>& cut, const char* what,
                               std::uint64_t seed) {
    SCOPED_TRACE(what);
    voxel_model reference_model = expand(w, cut);
    ASSERT_GT(reference_model.voxel_count(), 0u);
    chunked_world shown = w;
    shown.show(cut);
    dense_grid reference(reference_model);
    auto rays = mixed_rays(reference_model.bounds(), 6000, seed);
    std::vector<hit> expected(rays.size()), got(rays.size()), any(rays.size());
    tracer<cpu_scalar, dense_grid>(reference, cpu_options{1}).closest_hit(rays, expected);
    tracer<Backend, chunked_world> t(shown);
    t.closest_hit(rays, got);
    t.any_hit(rays, any);
    std::size_t hits = 0, mismatches = 0, ties = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        hits += expected[i].is_hit();
        agreement a = compare_hits(rays[i], expected[i], got[i]);
        if (a == agreement::mismatch && mismatches++ < 3)
            ADD_FAILURE() << "ray " << i << ": expected voxel (" << expected[i].voxel.x << " " << expected[i].voxel.y
                          << " " << expected[i].voxel.z << ") t " << expected[i].t << ", got (" << got[i].voxel.x << " "
                          << got[i].voxel.y << " " << got[i].voxel.z << ") t " << got[i].t << " hit " << got[i].is_hit();
        ties += a == agreement::tie;
        EXPECT_EQ(any[i].is_hit(), expected[i].is_hit()) << "ray " << i << " (any hit)";
    }
    EXPECT_EQ(mismatches, 0u);
    EXPECT_GT(hits, rays.size() / 5);
    std::printf("[%s] %zu rays, %zu hits, %zu ties, %zu mismatches, %llu chunks shown\n", what, rays.size(), hits, ties,
                mismatches, (unsigned long long)shown.stats().shown_chunks);
}

// A world of 16^3 chunks with negative coordinates and 4 LODs.
chunked_world lod_world() {
    world_options o;
    o.chunk_bits = 4;
    o.threads = 2;
    return chunked_world(world_test_model(), o);
}

template <class Backend>
void every_cut(const char* backend) {
    chunked_world w = lod_world();
    ASSERT_GE(w.grid().top_lod, 3);
    for (int lod = 0; lod <= w.grid().top_lod; ++lod)
        cut_matches_its_reference<Backend>(w, uniform_cut(w, lod), (std::string(backend) + " LOD " + std::to_string(lod)).c_str(),
                                           7 + std::uint64_t(lod));
    cut_matches_its_reference<Backend>(w, split_cut(w), (std::string(backend) + " split cut").c_str(), 99);
}

TEST(world_lod, the_lod0_cut_is_the_model) {
    voxel_model model = scenes::make_builtin("terrain:120", 2);
    world_options o;
    o.chunk_bits = 4;
    chunked_world w(model, o);
    voxel_model back = expand(w, uniform_cut(w, 0));
    EXPECT_EQ(back.voxel_count(), model.voxel_count());
    std::size_t differ = 0;
    model.for_each_voxel([&](glm::ivec3 p, std::uint8_t v) { differ += back.get(p) != v; });
    EXPECT_EQ(differ, 0u);
    // Coarser LODs hold fewer voxels, and the top one at most 2 chunks a side.
    for (int n = 1; n <= w.grid().top_lod; ++n) EXPECT_LT(w.stats().voxels[std::size_t(n)], w.stats().voxels[std::size_t(n) - 1]);
    EXPECT_LE(w.stats().chunks.back(), 8u);
}

TEST(world_lod, colour_worlds_average_colours_up_the_chain) {
    voxel_model model = scenes::make_builtin("terrain:64", 2);
    for (int i = 1; i < 256; ++i)
        model.palette()[std::uint8_t(i)].colour = rgba{std::uint8_t(i), std::uint8_t(255 - i), std::uint8_t(i / 2), 255};
    world_options o;
    o.chunk_bits = 4;
    o.attributes = svdag_attributes::colour_blocks;
    o.colour_error = 0.02f;
    chunked_world w(model, o);
    // LOD 1 voxel colours against the average of their LOD 0 children's palette colours.
    std::size_t checked = 0;
    for (auto& p : uniform_cut(w, 1)) {
        for (auto& v : decode_svdag(p.chunk->dag)) {
            glm::ivec3 lo = w.grid().origin + (((p.key.cell << 1) << 4) + (v.position << 1));
            int sum[3] = {}, n = 0;
            for (int k = 0; k < 8; ++k) {
                std::uint8_t m = model.get(lo + glm::ivec3(k & 1, (k >> 1) & 1, k >> 2));
                if (!m) continue;
                rgba c = model.palette()[m].colour;
                sum[0] += c.r, sum[1] += c.g, sum[2] += c.b, ++n;
            }
            ASSERT_GE(n, o.density);
            rgba average{std::uint8_t((sum[0] + n / 2) / n), std::uint8_t((sum[1] + n / 2) / n), std::uint8_t((sum[2] + n / 2) / n)};
            EXPECT_LE(colour_difference(v.attribute, average), svdag_build::colour_tolerance(o.colour_error));
            ++checked;
        }
    }
    EXPECT_GT(checked, 1000u);
}

template <class Backend>
struct world_lod_on : ::testing::Test {};
TYPED_TEST_SUITE(world_lod_on, every_backend, backend_names);

TYPED_TEST(world_lod_on, every_cut_traces_as_the_reference) { every_cut<TypeParam>(TypeParam::name); }

}  // namespace
}  // namespace voxray
