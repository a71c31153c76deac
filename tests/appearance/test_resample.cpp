// Coarser tables re-sampled from the level below through the walk (appearance/resample.hpp):
// the coarse voxels and their materials; a solid block keeps its colour and full opacity; a
// slab filling half of each coarse voxel reads opacity 1 across it and 1/2 along it; a
// plane's coarse table re-sampled from its fine one agrees with the coarse table made from
// its triangles; the same table for 1 and 2 threads; a six directions table is refused.
#include <gtest/gtest.h>

#include <cmath>

#include "walk_tables.hpp"
#include "voxray/appearance/record_codes.hpp"
#include "voxray/appearance/resample.hpp"
#include "voxray/cpu/appearance_walk.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/embree/triangle_scene.hpp"

namespace voxray {
namespace {

using namespace appearance;
using fine_walker = appearance_walker<kernels::dense_grid_kernel>;

fine_walker walker_of(const voxel_model& model, const appearance_table& table) {
    dense_grid grid(model);
    return fine_walker({grid.blob().begin(), grid.blob().end()}, table, 1);
}

// uniform_table with one colour for every voxel.
appearance_table one_colour_table(const voxel_model& model, std::uint32_t opacity_q, std::uint32_t rgb) {
    appearance_table t = test::uniform_table(model, opacity_q);
    for (std::size_t f = 0; f < t.faces.size(); f += VX_APP_FACE_WORDS)
        t.faces[f] = VX_APP_FACE_WORD0(rgb & 255u, (rgb >> 8) & 255u, (rgb >> 16) & 255u, 255u);
    return t;
}

float opacity_along(const appearance_table& t, std::size_t row, glm::vec3 d) {
    d = glm::normalize(d);
    const std::uint32_t* head = t.words.data() + row * VX_APP_COMPACT_WORDS;
    return kernels::scalar::vx_app_opacity(head[1], head[2], d.x, d.y, d.z);
}

TEST(appearance_resample, coarse_voxels_cover_their_children_with_the_most_frequent_material) {
    voxel_model fine;
    fine.set({-1, -1, -1}, 7);  // parent (-1, -1, -1): floor, not truncation
    fine.set({0, 0, 0}, 3), fine.set({1, 0, 0}, 5), fine.set({0, 1, 0}, 5), fine.set({1, 1, 1}, 3);
    fine.set({4, 0, 0}, 9);
    voxel_model coarse = coarser_voxels(fine);
    std::size_t count = 0;
    coarse.for_each_voxel([&](glm::ivec3, std::uint8_t) { ++count; });
    EXPECT_EQ(count, 3u);
    EXPECT_EQ(coarse.get({-1, -1, -1}), 7);
    EXPECT_EQ(coarse.get({0, 0, 0}), 3);  // 3 and 5 twice each: the smaller
    EXPECT_EQ(coarse.get({2, 0, 0}), 9);
}

TEST(appearance_resample, a_solid_block_keeps_its_colour_and_full_opacity) {
    voxel_model fine;
    for (int z = 0; z < 8; ++z)
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) fine.set({x, y, z}, 1);
    const std::uint32_t rgb = 40u | 150u << 8 | 220u << 16;
    fine_walker walker = walker_of(fine, one_colour_table(fine, 15, rgb));
    appearance_table coarse = resample(walker, coarser_voxels(fine), {.kind = record_kind::averages, .threads = 2});
    ASSERT_EQ(coarse.voxels.size(), 64u);
    for (std::size_t row = 0; row < coarse.voxels.size(); ++row) {
        std::uint32_t w0 = coarse.words[row * VX_APP_AVERAGES_WORDS];
        EXPECT_EQ(VX_APP_AVG_OPACITY(w0), 255u) << row;
        EXPECT_EQ(w0 & 0xFFFFFFu, rgb) << row;
    }
}

TEST(appearance_resample, a_slab_filling_half_of_each_coarse_voxel_reads_its_coverage) {
    voxel_model fine;  // fine z = 0: the lower half of coarse z = 0
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x) fine.set({x, y, 0}, 1);
    fine_walker walker = walker_of(fine, one_colour_table(fine, 15, 0x808080u));
    appearance_table coarse = resample(walker, coarser_voxels(fine),
                                       {.kind = record_kind::compact, .opacity_strata = 4, .threads = 2});
    ASSERT_EQ(coarse.voxels.size(), 16u);
    for (std::size_t row = 0; row < coarse.voxels.size(); ++row) {
        EXPECT_EQ(opacity_along(coarse, row, {0, 0, 1}), 1.0f) << row;
        EXPECT_NEAR(opacity_along(coarse, row, {1, 0, 0}), 0.5f, 1.0f / 15.0f) << row;
        EXPECT_NEAR(opacity_along(coarse, row, {0, 1, 0}), 0.5f, 1.0f / 15.0f) << row;
    }
}

// An 8 x 8 world-unit plane at z = 1.5, double-sided, of one colour.
io::triangle_mesh plane() {
    io::triangle_mesh m;
    m.positions = {{0, 0, 1.5}, {8, 0, 1.5}, {8, 8, 1.5}, {0, 8, 1.5}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    m.group_names = {"plane"};
    io::mesh_material mat;
    mat.base_colour = {0.6f, 0.3f, 0.1f, 1.0f}, mat.double_sided = true;
    m.surface.materials = {mat};
    m.surface.triangle_materials = {0, 0};
    return m;
}

// Voxels of `scale` per world unit over the plane's 8 x 8 units.
io::voxel_grid_map grid(double scale) {
    io::voxel_grid_map g;
    g.scale = scale, g.dims = glm::ivec3(int(8 * scale));
    return g;
}

voxel_model plane_voxels(int size, int z) {
    voxel_model v;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) v.set({x, y, z}, 1);
    return v;
}

TEST(appearance_resample, a_planes_resampled_table_agrees_with_the_one_from_its_triangles) {
    io::triangle_mesh mesh = plane();
    const precompute_options o{.kind = record_kind::compact, .opacity_strata = 4, .threads = 2};
    embree::triangle_scene fine_scene(mesh, grid(1.0)), coarse_scene(mesh, grid(0.5));
    voxel_model fine = plane_voxels(8, 1), coarse = coarser_voxels(fine);
    fine_walker walker = walker_of(fine, precompute(fine_scene, mesh, fine, o));
    appearance_table resampled = resample(walker, coarse, o);
    appearance_table direct = precompute(coarse_scene, mesh, coarse, o);
    ASSERT_EQ(resampled.voxels, direct.voxels);
    ASSERT_EQ(resampled.voxels.size(), 16u);
    for (std::size_t row = 0; row < direct.voxels.size(); ++row) {
        for (unsigned k = 0; k < VX_APP_DIRECTIONS; ++k) {
            glm::vec3 d(VX_APP_DIR(k, 0u), VX_APP_DIR(k, 1u), VX_APP_DIR(k, 2u));
            EXPECT_NEAR(opacity_along(resampled, row, d), opacity_along(direct, row, d), 0.15f)
                << "row " << row << " direction " << k;
        }
        for (const appearance_table* t : {&resampled, &direct}) {  // the plane's colour and normal
            std::uint32_t first = t->words[row * VX_APP_COMPACT_WORDS];
            std::uint32_t f0 = t->faces[first * VX_APP_FACE_WORDS], f1 = t->faces[first * VX_APP_FACE_WORDS + 1];
            EXPECT_NEAR(srgb_cubic(VX_APP_FACE_R(f0)), 0.6, 0.02) << row;
            EXPECT_NEAR(srgb_cubic(VX_APP_FACE_G(f0)), 0.3, 0.02) << row;
            EXPECT_NEAR(srgb_cubic(VX_APP_FACE_B(f0)), 0.1, 0.02) << row;
            glm::vec3 n = from_octahedral(
                {from_snorm(VX_APP_FACE_NORMAL_U(f1), 12), from_snorm(VX_APP_FACE_NORMAL_V(f1), 12)});
            EXPECT_GT(std::abs(n.z), 0.95f) << row << (t == &direct ? " from triangles" : " re-sampled");
        }
    }
    // The same table for 1 and 2 threads.
    precompute_options one = o;
    one.threads = 1;
    appearance_table again = resample(walker, coarse, one);
    EXPECT_EQ(again.words, resampled.words);
    EXPECT_EQ(again.faces, resampled.faces);
}

TEST(appearance_resample, a_six_directions_table_is_not_a_finer_level) {
    voxel_model fine = plane_voxels(4, 0);
    appearance_table six;
    six.kind = record_kind::six;
    six.record_words = VX_APP_SIX_WORDS;
    fine.for_each_voxel([&](glm::ivec3 p, std::uint8_t) { six.voxels.push_back(p); });
    std::sort(six.voxels.begin(), six.voxels.end(), ordinal_less);
    six.words.assign(six.voxels.size() * VX_APP_SIX_WORDS, 0);
    fine_walker walker = walker_of(fine, six);
    try {
        resample(walker, coarser_voxels(fine));
        FAIL() << "no error";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("six directions"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace voxray
