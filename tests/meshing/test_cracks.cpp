// Crack tests of POP chunk meshes over many chunks with T-junctions, at negative
// coordinates too: closedness at every level before and after the squashed-face pass, and
// over 10^4 random views, shared vertices and T-vertices after morphing.
#include <gtest/gtest.h>

#include "meshing_models.hpp"
#include "voxray/check/mesh_cracks.hpp"
#include "voxray/check/mesh_faces.hpp"
#include "voxray/meshing/chunk_source.hpp"
#include "voxray/meshing/mesher.hpp"
#include "voxray/meshing/squashed.hpp"
#include "voxray/scenes/chunk_scenes.hpp"

namespace voxray {
namespace {

std::vector<meshing::chunk_mesh> mesh_model(const voxel_model& model, bool ao) {
    std::vector<meshing::chunk_mesh> meshes;
    meshing::mesher mesher({.ambient_occlusion = ao});
    meshing::chunk_voxels c;
    std::vector<std::uint8_t> scratch;
    for (glm::ivec3 origin : meshing::chunk_origins(model)) {
        meshing::fill_chunk(model, origin, c, scratch);
        meshes.push_back(mesher.mesh(c));
    }
    return meshes;
}

const box3i region{{-64, -64, -64}, {64, 64, 64}};

TEST(cracks, closed_at_every_level_before_and_after_the_squashed_face_pass) {
    for (std::uint64_t seed : {11u, 12u}) {
        auto meshes = mesh_model(test::blob_model(seed, region, 10, 2), seed == 12);
        for (int level = 0; level < VX_MESH_LEVELS; ++level) EXPECT_EQ(check::open_lines(meshes, level), 0u) << "level " << level;
        for (auto& m : meshes) {
            meshing::chunk_mesh before = m;
            meshing::remove_squashed_faces(m);
            EXPECT_EQ(check::pop_order_problem(m, false), "");
            EXPECT_EQ(check::face_set_mismatches(check::expand_quads(before), check::expand_quads(m)), 0u);
            for (int level = 1; level < VX_MESH_LEVELS; ++level)
                EXPECT_EQ(check::coverage_changes(before, m, level), 0u) << "level " << level;
        }
    }
}

TEST(cracks, the_squashed_face_pass_keeps_noise_covered_and_cuts_its_overdraw) {
    for (const char* name : {"noise50", "checker"}) {
        auto meshes = mesh_model(scenes::make_chunk_scene(name), false);
        ASSERT_EQ(meshes.size(), 1u);
        const std::vector<meshing::chunk_mesh> before_all = meshes;
        const meshing::chunk_mesh& before = before_all[0];
        auto& m = meshes[0];
        EXPECT_GT(meshing::remove_squashed_faces(m).moved, 0u) << name;
        EXPECT_EQ(check::pop_order_problem(m, false), "") << name;
        for (int level = 0; level < VX_MESH_LEVELS; ++level) {
            EXPECT_EQ(check::open_lines(before_all, level), 0u) << name << " level " << level;
            EXPECT_EQ(check::coverage_changes(before, m, level), 0u) << name << " level " << level;
            EXPECT_LE(meshing::overdraw(m, level).ratio(), meshing::overdraw(before, level).ratio()) << name << " level " << level;
        }
    }
}

TEST(cracks, shared_vertices_and_t_vertices_over_ten_thousand_views) {
    auto meshes = mesh_model(test::blob_model(21, region, 10, 2), false);
    auto cases = check::find_morph_cases(meshes);
    ASSERT_GT(cases.shared.size(), 100u);
    ASSERT_GT(cases.t_junctions.size(), 100u);
    auto r = check::check_morphs(meshes, cases, region, 10000, 5);
    EXPECT_EQ(r.split_vertices, 0u) << r.shared_checks << " checks";
    EXPECT_EQ(r.t_vertices_off, 0u) << r.t_checks << " checks";
    std::printf("%zu shared vertices, %zu T-junctions, %llu views\n", cases.shared.size(), cases.t_junctions.size(),
                (unsigned long long)r.views);
}

}  // namespace
}  // namespace voxray
