// The mesher against brute force: the canonical face set (every visible unit face with its
// material and AO) of each chunk, POP order and its table, the occupancy paths, and the
// edge cases (empty, full, misaligned).
#include <gtest/gtest.h>

#include <random>

#include "meshing_models.hpp"
#include "voxray/check/mesh_faces.hpp"
#include "voxray/brickmap/read_box.hpp"
#include "voxray/check/random_edits.hpp"
#include "voxray/dense_grid/read_box.hpp"
#include "voxray/meshing/bit_transpose.hpp"
#include "voxray/meshing/chunk_source.hpp"
#include "voxray/meshing/mesher.hpp"
#include "voxray/naadf/read_box.hpp"
#include "voxray/scenes/chunk_scenes.hpp"
#include "voxray/svdag/read_box.hpp"

namespace voxray {
namespace {

using meshing::chunk_voxels;

chunk_voxels chunk_at(const voxel_model& m, glm::ivec3 origin) {
    chunk_voxels c;
    std::vector<std::uint8_t> scratch;
    meshing::fill_chunk(m, origin, c, scratch);
    return c;
}

// Meshes `c` and compares with brute force; returns the mesh.
meshing::chunk_mesh expect_canonical(const chunk_voxels& c, bool ao, const std::string& what) {
    meshing::mesher mesher({.ambient_occlusion = ao});
    meshing::chunk_mesh m = mesher.mesh(c);
    auto expected = check::brute_force_faces(c, ao);
    auto got = check::expand_quads(m);
    EXPECT_EQ(check::face_set_mismatches(expected, got), 0u) << what << (ao ? " (AO)" : "") << ": " << expected.size()
                                                              << " faces expected, " << got.size() << " from the quads";
    EXPECT_EQ(check::pop_order_problem(m), "") << what;
    return m;
}

TEST(mesher, chunk_scenes_give_the_brute_force_face_set) {
    for (const char* name : {"sphere30", "checker", "noise50", "terrain64"}) {
        voxel_model model = scenes::make_chunk_scene(name);
        chunk_voxels c = chunk_at(model, {0, 0, 0});
        for (bool ao : {false, true}) {
            auto m = expect_canonical(c, ao, name);
            if (std::string(name) == "checker") {
                EXPECT_EQ(m.quad_count(), 64u * 64 * 64 / 2 * 6);  // nothing merges
            }
        }
    }
}

TEST(mesher, blobs_across_chunk_sides_and_negative_coordinates) {
    for (std::uint64_t seed : {1u, 2u, 3u}) {
        voxel_model model = test::blob_model(seed, box3i{{-90, -70, -66}, {70, 60, 64}});
        for (glm::ivec3 origin : meshing::chunk_origins(model)) {
            chunk_voxels c = chunk_at(model, origin);
            std::string what = "seed " + std::to_string(seed) + " chunk at (" + std::to_string(origin.x) + ", " +
                               std::to_string(origin.y) + ", " + std::to_string(origin.z) + ")";
            for (bool ao : {false, true}) expect_canonical(c, ao, what);
        }
    }
}

// Every structure with a read_box hands the mesher the chunks of its model: materials,
// occupancy rows, shell, and so the same quads; also for chunks it only partly covers or
// not at all, and (the editable ones) after the same edits on both.
template <class Structure>
class structure_source : public ::testing::Test {};
using sources = ::testing::Types<dense_grid, brickmap<>, naadf, svdag>;
TYPED_TEST_SUITE(structure_source, sources);

template <class Structure>
void expect_same_chunks(const voxel_model& model, const Structure& structure, std::vector<glm::ivec3> origins,
                        const std::string& when) {
    meshing::mesher mesher;
    std::vector<std::uint8_t> scratch;
    for (glm::ivec3 origin : origins) {
        chunk_voxels from_model, from_structure;
        meshing::fill_chunk(model, origin, from_model, scratch);
        meshing::fill_chunk(structure, origin, from_structure, scratch);
        std::string where = when + ", chunk at " + std::to_string(origin.x) + ", " + std::to_string(origin.y) + ", " +
                            std::to_string(origin.z);
        EXPECT_EQ(from_structure.material, from_model.material) << where;
        EXPECT_EQ(from_structure.rows, from_model.rows) << where;
        EXPECT_EQ(from_structure.x_lo, from_model.x_lo) << where;
        EXPECT_EQ(from_structure.x_hi, from_model.x_hi) << where;
        EXPECT_EQ(mesher.mesh(from_structure).words, mesher.mesh(from_model).words) << where;
    }
}

TYPED_TEST(structure_source, hands_out_the_chunks_of_its_model) {
    box3i area{{-90, -70, -66}, {70, 60, 64}};
    voxel_model model = test::blob_model(4, area);
    TypeParam structure(model);
    auto origins = meshing::chunk_origins(model);
    origins.push_back({-192, 0, 0});  // beyond the structure: empty
    expect_same_chunks(model, structure, origins, "built");
    if constexpr (requires { structure.apply(regions::box{}, edit_op::fill, std::uint8_t(1)); }) {
        for (const region_edit& e : random_edits(area, 40, 7)) {
            apply_to_model(model, e, area);
            std::visit([&](const auto& region) { structure.apply(region, e.op, std::uint8_t(e.value)); }, e.region);
        }
        for (glm::ivec3 origin : meshing::chunk_origins(model)) origins.push_back(origin);  // and chunks edits reached
        expect_same_chunks(model, structure, origins, "after 40 edits");
    }
}

// A colour-block DAG holds colours, not materials: reading it for a mesh is refused.
TEST(mesher, a_colour_block_dag_is_no_chunk_source) {
    voxel_model model = test::blob_model(4, box3i{{0, 0, 0}, {60, 60, 60}});
    svdag_colours dag(model);
    chunk_voxels c;
    std::vector<std::uint8_t> scratch;
    try {
        meshing::fill_chunk(dag, {0, 0, 0}, c, scratch);
        ADD_FAILURE() << "a colour-block DAG was read as materials";
    } catch (const voxray::error& e) {
        EXPECT_NE(std::string(e.what()).find("holds colour blocks"), std::string::npos) << e.what();
    }
}

TEST(mesher, merges_faces_inside_the_border_ring_only) {
    // A solid 64^3 cube alone: each side is a plane on the chunk's side. Its ring of
    // 4 * 63 faces stays unit quads, the 62 x 62 inside is one quad.
    voxel_model model;
    for (int z = 0; z < 64; ++z)
        for (int y = 0; y < 64; ++y)
            for (int x = 0; x < 64; ++x) model.set({x, y, z}, 7);
    auto m = expect_canonical(chunk_at(model, {0, 0, 0}), false, "solid cube");
    EXPECT_EQ(m.quad_count(), 6u * (4 * 63 + 1));
    for (std::uint32_t i = 0; i < m.quad_count(); ++i) {
        meshing::quad q = m.at(i);
        if (q.w > 1 || q.h > 1) {
            EXPECT_EQ(q.w, 62);
            EXPECT_EQ(q.h, 62);
        }
    }
}

TEST(mesher, empty_and_buried_chunks_have_no_quads) {
    voxel_model model;
    for (int z = -1; z < 65; ++z)
        for (int y = -1; y < 65; ++y)
            for (int x = -1; x < 65; ++x) model.set({x, y, z}, 3);
    EXPECT_EQ(expect_canonical(chunk_at(model, {0, 0, 0}), true, "buried").quad_count(), 0u);
    auto empty = expect_canonical(chunk_at(voxel_model{}, {-64, 0, 64}), true, "empty");
    EXPECT_EQ(empty.quad_count(), 0u);
    for (auto e : empty.table) EXPECT_EQ(e, 0u);
}

TEST(mesher, a_misaligned_origin_is_an_error) {
    chunk_voxels c;
    std::vector<std::uint8_t> scratch;
    try {
        meshing::fill_chunk(voxel_model{}, {32, 0, 0}, c, scratch);
        FAIL() << "no error";
    } catch (const error& e) {
        EXPECT_NE(std::string(e.what()).find("not a multiple of 64"), std::string::npos) << e.what();
    }
}

TEST(mesher, pop_off_keeps_emission_order_and_every_quad_in_every_prefix) {
    voxel_model model = scenes::make_chunk_scene("terrain64");
    chunk_voxels c = chunk_at(model, {0, 0, 0});
    meshing::mesher plain({.pop_order = false});
    meshing::chunk_mesh m = plain.mesh(c);
    EXPECT_EQ(check::face_set_mismatches(check::brute_force_faces(c, false), check::expand_quads(m)), 0u);
    for (int f = 0; f < VX_MESH_FACES; ++f)
        for (int lod = 0; lod < VX_MESH_LEVELS; ++lod) EXPECT_EQ(m.face_end(f, lod), m.face_end(f, 0));
}

TEST(mesher, occupancy_paths_agree_with_the_bytes) {
    std::mt19937 g(3);
    std::vector<std::uint8_t> bytes(64 * 200);
    for (auto& b : bytes) b = (g() % 3 == 0) ? std::uint8_t(g()) : 0;
    std::vector<std::uint64_t> rows(200), reference(200);
    meshing::occupancy_rows(bytes.data(), 200, rows.data());
    meshing::occupancy_detail::rows_scalar(bytes.data(), 200, reference.data());
    for (int r = 0; r < 200; ++r) {
        std::uint64_t expected = 0;
        for (int x = 0; x < 64; ++x) expected |= std::uint64_t(bytes[r * 64 + x] != 0) << x;
        EXPECT_EQ(rows[r], expected) << "row " << r << " on " << meshing::occupancy_path_name();
        EXPECT_EQ(reference[r], expected) << "row " << r << " scalar";
    }
}

TEST(mesher, bit_transpose_on_every_path) {
    std::mt19937_64 g(9);
    for (int path = 0; path < 2; ++path) {
        if (path == 1 && !meshing::transpose64_has_gfni()) GTEST_SKIP() << "this CPU has no GFNI: the scalar path was tested";
        std::uint64_t a[64], b[64];
        for (int i = 0; i < 64; ++i) a[i] = b[i] = g();
        if (path == 0) meshing::transpose64_scalar(b);
#if defined(__x86_64__)
        else meshing::transpose64_gfni(b);
#endif
        for (int i = 0; i < 64; ++i)
            for (int j = 0; j < 64; ++j) ASSERT_EQ((b[i] >> j) & 1, (a[j] >> i) & 1) << "path " << path << ": " << i << ", " << j;
    }
}

}  // namespace
}  // namespace voxray
