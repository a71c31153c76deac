// Remeshing after edits (meshing/remesh.hpp): only the chunks an edit can change are read
// and meshed again, and the meshes kept equal meshing every chunk of the edited structure
// from scratch, on the brickmap and NAADF, with and without AO; an edit one voxel beyond a
// chunk's side changes that chunk's faces and AO too.
#include <gtest/gtest.h>

#include <string>
#include <variant>
#include <vector>

#include "meshing_models.hpp"
#include "voxray/brickmap/read_box.hpp"
#include "voxray/check/random_edits.hpp"
#include "voxray/meshing/remesh.hpp"
#include "voxray/naadf/read_box.hpp"

namespace voxray {
namespace {

std::string where(glm::ivec3 p) {
    return std::to_string(p.x) + ", " + std::to_string(p.y) + ", " + std::to_string(p.z);
}

// `kept` holds exactly the meshes of every chunk of `structure` (whose voxels are `model`'s).
template <class Structure>
void expect_current(const meshing::chunk_meshes& kept, const Structure& structure, const voxel_model& model,
                    meshing::mesher_options options, const std::string& when) {
    meshing::chunk_meshes fresh(options);
    auto origins = meshing::chunk_origins(model);
    fresh.mesh(structure, origins);
    EXPECT_EQ(kept.by_origin().size(), fresh.by_origin().size()) << when;
    for (const auto& [origin, mesh] : fresh.by_origin()) {
        auto it = kept.by_origin().find(origin);
        if (it == kept.by_origin().end()) {
            ADD_FAILURE() << when << ": no mesh kept for chunk " << where(origin);
            continue;
        }
        EXPECT_EQ(it->second.words, mesh.words) << when << ", chunk " << where(origin);
        EXPECT_EQ(it->second.table, mesh.table) << when << ", chunk " << where(origin);
    }
}

template <class Structure>
class remesh_after_edits : public ::testing::Test {};
using editable = ::testing::Types<brickmap<>, naadf>;
TYPED_TEST_SUITE(remesh_after_edits, editable);

TYPED_TEST(remesh_after_edits, equals_meshing_everything_again) {
    const box3i area{{-90, -70, -66}, {70, 60, 64}};
    for (bool ao : {false, true}) {
        voxel_model model = test::blob_model(5, area);
        TypeParam structure(model);
        meshing::mesher_options options{.ambient_occlusion = ao};
        meshing::chunk_meshes kept(options);
        auto origins = meshing::chunk_origins(model);
        kept.mesh(structure, origins);
        for (int round = 0; round < 3; ++round) {
            std::vector<box3i> edited;
            for (const region_edit& e : random_edits(area, 6, 20 + std::uint64_t(round))) {
                apply_to_model(model, e, area);
                std::visit(
                    [&](const auto& region) {
                        structure.apply(region, e.op, std::uint8_t(e.value));
                        edited.push_back(region.bounds());
                    },
                    e.region);
            }
            meshing::remesh_stats stats = kept.remesh(structure, edited);
            EXPECT_EQ(stats.chunks, meshing::chunks_to_remesh(edited).size());
            expect_current(kept, structure, model, options, "round " + std::to_string(round) + (ao ? ", AO" : ""));
        }
    }
}

// A slab that ends at x = 63 (chunk 0's +x side), then voxels filled at x = 64..69 (chunk
// 64's): the slab's +x faces go, and the AO of its faces beside the side changes.
TYPED_TEST(remesh_after_edits, an_edit_beyond_a_side_changes_the_neighbour) {
    voxel_model model;
    for (int z = 0; z < 20; ++z)
        for (int y = 0; y < 20; ++y)
            for (int x = 40; x < 64; ++x) model.set({x, y, z}, 3);
    TypeParam structure(model);
    meshing::mesher_options options{.ambient_occlusion = true};
    meshing::chunk_meshes kept(options);
    auto origins = meshing::chunk_origins(model);
    kept.mesh(structure, origins);
    const box3i filled{{64, 2, 2}, {70, 18, 18}};
    structure.fill_box(filled, 5);
    for (int z = filled.min.z; z < filled.max.z; ++z)
        for (int y = filled.min.y; y < filled.max.y; ++y)
            for (int x = filled.min.x; x < filled.max.x; ++x) model.set({x, y, z}, 5);
    auto touched = meshing::chunks_to_remesh(std::span(&filled, 1));
    EXPECT_NE(std::find(touched.begin(), touched.end(), glm::ivec3(0)), touched.end());
    kept.remesh(structure, std::span(&filled, 1));
    expect_current(kept, structure, model, options, "after the fill beyond the side");
}

TEST(remesh, chunks_to_remesh_grows_each_box_by_one_voxel) {
    std::vector<box3i> boxes{{{0, 0, 0}, {1, 1, 1}}, {{70, 10, 10}, {71, 11, 11}}, {{-5, 5, 5}, {-5, 6, 6}}};
    auto touched = meshing::chunks_to_remesh(boxes);  // the empty third box touches nothing
    std::vector<glm::ivec3> expected{{-64, -64, -64}, {0, -64, -64}, {-64, 0, -64}, {0, 0, -64},
                                     {-64, -64, 0},   {0, -64, 0},   {-64, 0, 0},   {0, 0, 0},   {64, 0, 0}};
    EXPECT_EQ(touched, expected);
}

}  // namespace
}  // namespace voxray
