// The mesher kernel (meshing/kernel.h) on every backend against the CPU mesher: the same
// words in the same POP order and the same table, bit for bit, with AO on and off; empty
// and full chunks; several chunks at once; a chunk over the mesh buffer is an error with
// the numbers.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "meshing_models.hpp"
#include "test_data.hpp"
#include "typed_cases.hpp"
#include "voxray/io/vox_reader.hpp"
#include "voxray/meshing/chunk_source.hpp"
#include "voxray/meshing/kernel_meshers.hpp"
#include "voxray/meshing/mesher.hpp"
#include "voxray/scenes/chunk_scenes.hpp"

namespace voxray {
namespace {

using meshing::chunk_mesh;
using meshing::chunk_voxels;

using kernel_meshers = test::gtest_types<meshing::kernel_meshers>::type;

template <class Mesher>
class mesher_kernel : public ::testing::Test {};
TYPED_TEST_SUITE(mesher_kernel, kernel_meshers);

std::vector<chunk_voxels> chunks_of(const voxel_model& model, std::size_t most = 4) {
    std::vector<chunk_voxels> chunks;
    std::vector<std::uint8_t> scratch;
    for (glm::ivec3 origin : meshing::chunk_origins(model)) {
        if (chunks.size() == most) break;
        meshing::fill_chunk(model, origin, chunks.emplace_back(), scratch);
    }
    return chunks;
}

// The kernel's meshes of `chunks` equal the CPU mesher's, word for word.
template <class Mesher>
void expect_cpu_meshes(const std::vector<chunk_voxels>& chunks, meshing::mesher_options options,
                       const std::string& what) {
    Mesher kernel(options);
    std::vector<chunk_mesh> got = kernel.mesh(chunks);
    ASSERT_EQ(got.size(), chunks.size()) << what;
    meshing::mesher cpu(options);
    for (std::size_t i = 0; i < chunks.size(); ++i) {
        chunk_mesh expected = cpu.mesh(chunks[i]);
        std::string where = what + ", chunk " + std::to_string(i) + (options.ambient_occlusion ? " (AO)" : "") +
                            (options.pop_order ? "" : " (no POP)") + " on " + kernel.device_name();
        EXPECT_EQ(got[i].origin, expected.origin) << where;
        EXPECT_EQ(got[i].table, expected.table) << where;
        ASSERT_EQ(got[i].words.size(), expected.words.size()) << where;
        std::size_t differing = 0, first = 0;
        for (std::size_t w = 0; w < expected.words.size(); ++w)
            if (got[i].words[w] != expected.words[w] && differing++ == 0) first = w;
        EXPECT_EQ(differing, 0u) << where << ": first at word " << first << " of " << expected.words.size();
    }
}

TYPED_TEST(mesher_kernel, chunk_scenes_give_the_cpu_meshes) {
    for (const char* name : {"sphere30", "terrain64", "noise50", "checker"}) {
        std::vector<chunk_voxels> chunks = chunks_of(scenes::make_chunk_scene(name));
        for (bool ao : {false, true}) expect_cpu_meshes<TypeParam>(chunks, {.ambient_occlusion = ao}, name);
    }
}

TYPED_TEST(mesher_kernel, chunks_across_sides_at_negative_coordinates_at_once) {
    voxel_model model = test::blob_model(5, box3i{{-90, -70, -66}, {70, 60, 64}});
    std::vector<chunk_voxels> chunks = chunks_of(model, 6);
    ASSERT_EQ(chunks.size(), 6u);
    expect_cpu_meshes<TypeParam>(chunks, {.ambient_occlusion = true}, "blobs");
    expect_cpu_meshes<TypeParam>(chunks, {.pop_order = false}, "blobs");
}

TYPED_TEST(mesher_kernel, a_shared_scene_gives_the_cpu_meshes) {
    VOXRAY_REQUIRE_DATA();
    auto file = *test::data_dir() / "vox" / "minecraft_tree.vox";
    ASSERT_TRUE(std::filesystem::exists(file)) << file;
    expect_cpu_meshes<TypeParam>(chunks_of(io::load_vox(file), 3), {.ambient_occlusion = true}, "minecraft_tree.vox");
}

TYPED_TEST(mesher_kernel, empty_and_full_chunks) {
    chunk_voxels empty, full;
    std::fill(full.material.begin(), full.material.end(), std::uint8_t(2));
    full.update_interior_rows();
    full.origin = {-64, 0, 64};
    std::vector<chunk_voxels> chunks{empty, full};
    TypeParam kernel;
    std::vector<chunk_mesh> got = kernel.mesh(chunks);
    ASSERT_EQ(got.size(), 2u);
    EXPECT_EQ(got[0].quad_count(), 0u);
    EXPECT_EQ(got[1].quad_count(), meshing::mesher().mesh(full).quad_count());
    EXPECT_GT(got[1].quad_count(), 0u);
    expect_cpu_meshes<TypeParam>(chunks, {}, "empty and full");
    EXPECT_TRUE(kernel.mesh({}).empty());
}

TYPED_TEST(mesher_kernel, a_chunk_over_the_mesh_buffer_is_an_error_with_the_numbers) {
    std::vector<chunk_voxels> chunks = chunks_of(scenes::make_chunk_scene("noise50"), 1);
    std::size_t quads = meshing::mesher().mesh(chunks[0]).quad_count();
    TypeParam kernel;
    try {
        kernel.mesh(chunks, 1000);
        FAIL() << "a chunk of " << quads << " quads went into a buffer of 1000 a chunk";
    } catch (const error& e) {
        std::string message = e.what();
        EXPECT_NE(message.find(std::to_string(quads) + " quads"), std::string::npos) << message;
        EXPECT_NE(message.find("1000"), std::string::npos) << message;
    }
    // Left on the device, the chunk is counted but not written; reading it back says so.
    EXPECT_NO_THROW(kernel.run(chunks, 1000));
    EXPECT_THROW(kernel.read_meshes(chunks), error);
    EXPECT_THROW(kernel.mesh(chunks, meshing::most_chunk_quads + 1), error);
    EXPECT_EQ(kernel.mesh(chunks, std::uint32_t(quads))[0].quad_count(), quads);  // exactly full fits
}

}  // namespace
}  // namespace voxray
