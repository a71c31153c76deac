// Issue 27: a world built in shards (world/build/sharded_build.hpp) is byte for byte the
// world one process builds, however it is split; shares are balanced and cover every
// unit once; interrupted shards resume; shards of other arguments and unfinished shards
// are refused with the difference named.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "error_of.hpp"
#include "temp_dir.hpp"
#include "test_data.hpp"
#include "voxray/io/mesh_loader.hpp"
#include "voxray/world/build/mesh_source.hpp"
#include "voxray/world/build/model_source.hpp"
#include "voxray/world/build/sharded_build.hpp"
#include "world_test_model.hpp"

namespace voxray::test {
namespace {

namespace fs = std::filesystem;

// Every file under `dir` (relative path -> bytes).
std::map<std::string, std::string> folder_bytes(const fs::path& dir) {
    std::map<std::string, std::string> out;
    for (auto& e : fs::recursive_directory_iterator(dir)) {
        if (!e.is_regular_file()) continue;
        std::ifstream in(e.path(), std::ios::binary);
        out[fs::relative(e.path(), dir).string()] = {std::istreambuf_iterator<char>(in), {}};
    }
    return out;
}

// "" when f returns, else what it threw (for threads, where a throw would end the test).
std::string error_of_none(const std::function<void()>& f) {
    try {
        f();
    } catch (const std::exception& e) {
        return e.what();
    }
    return "";
}

template <class Source>
void expect_same_world_however_split(const Source& source, const world_build_options& o, std::vector<unsigned> splits) {
    temp_dir whole;
    build_world(source, whole.path, o);
    auto expected = folder_bytes(whole.path);
    ASSERT_GT(expected.size(), 10u);
    for (unsigned n : splits) {
        SCOPED_TRACE("shards: " + std::to_string(n));
        temp_dir dir;
        for (unsigned k = n; k-- > 0;) build_world(source, dir.path, o, {k, n});  // any order
        EXPECT_FALSE(fs::exists(manifest_path(dir.path))) << "a sharded build is unfinished until the finish";
        finish_world_build(source, dir.path, o);
        EXPECT_EQ(folder_bytes(dir.path), expected);
    }
}

TEST(world_shards, a_sharded_build_is_byte_identical_to_one_process) {
    expect_same_world_however_split(model_source(world_test_model()), small_chunks(), {1, 3, 4});
}

TEST(world_shards, a_tiled_scene_in_shards_running_at_once_is_byte_identical) {
    voxel_model tile = scenes::make_builtin("terrain:64", 2);
    model_source source(tile, {3, 1, 2});
    world_build_options o = small_chunks(1);
    temp_dir whole, dir;
    build_world(source, whole.path, o);
    std::vector<std::thread> shards;
    for (unsigned k = 0; k < 3; ++k)
        shards.emplace_back([&, k] { EXPECT_EQ(error_of_none([&] { build_world(source, dir.path, o, {k, 3}); }), ""); });
    for (auto& t : shards) t.join();
    finish_world_build(source, dir.path, o);
    EXPECT_EQ(folder_bytes(dir.path), folder_bytes(whole.path));
}

TEST(world_shards, a_shared_mesh_in_shards_is_byte_identical) {
    VOXRAY_REQUIRE_DATA();
    io::triangle_mesh mesh = io::load_mesh(*data_dir() / "mesh" / "stanford_bunny.ply");
    world_build_options o = small_chunks();
    o.chunk_bits = 5;
    expect_same_world_however_split(mesh_source(mesh, 96), o, {3});  // small: this runs under the sanitizers too
}

TEST(world_shards, shares_cover_every_unit_once_and_balance_the_work) {
    // Skewed work: one heavy cell among many light ones, and a heavy band.
    std::vector<glm::ivec3> cells;
    std::vector<std::uint64_t> work;
    for (int z = 0; z < 8; ++z)
        for (int y = 0; y < 8; ++y)
            for (int x = 0; x < 8; ++x) cells.push_back({x, y, z}), work.push_back(x == 3 ? 50 : 1 + (x * y) % 5);
    work[100] = 4000;
    std::sort(cells.begin(), cells.end(), ivec3_less{});
    for (unsigned n : {1u, 2u, 5u, 16u}) {
        auto split = shard_split::make(cells, work, 3, n);
        EXPECT_GE(split.units.size(), std::min<std::size_t>(cells.size(), 8 * n));
        std::vector<int> owners(split.units.size(), 0);
        std::uint64_t total = 0, heaviest = 0;
        for (auto& u : split.units) total += u.work, heaviest = std::max(heaviest, u.work);
        for (unsigned k = 0; k < n; ++k) {
            std::uint64_t share = 0;
            for (std::size_t u : split.share(k, n)) ++owners[u], share += split.units[u].work;
            EXPECT_LE(share, total / n + heaviest) << "shard " << k << " of " << n;
        }
        for (int o : owners) EXPECT_EQ(o, 1);
    }
}

TEST(world_shards, an_interrupted_shard_and_finish_resume) {
    voxel_model model = world_test_model();  // the source holds a pointer to it
    model_source source(model);
    world_build_options o = small_chunks();
    temp_dir whole, dir;
    build_world(source, whole.path, o);
    world_build_options stops = o;
    int calls = 0;
    stops.progress = [&](const world_build_progress&) {
        if (++calls == 6) throw std::runtime_error("killed");
    };
    EXPECT_THROW(build_world(source, dir.path, stops, {1, 2}), std::runtime_error);
    build_world(source, dir.path, o, {0, 2});
    std::string unfinished = error_of([&] { finish_world_build(source, dir.path, o); });
    EXPECT_NE(unfinished.find("shard 1 of 2 has not finished"), std::string::npos) << unfinished;
    auto resumed = build_world(source, dir.path, o, {1, 2});
    EXPECT_GE(resumed.lods[0].resumed, 3u) << "the chunks written before the stop are kept";
    calls = 0;
    EXPECT_THROW(finish_world_build(source, dir.path, stops), std::runtime_error);
    finish_world_build(source, dir.path, o);
    EXPECT_EQ(folder_bytes(dir.path), folder_bytes(whole.path));
}

TEST(world_shards, shards_of_other_arguments_are_refused_naming_the_difference) {
    voxel_model model = world_test_model();
    model_source source(model);
    world_build_options o = small_chunks();
    temp_dir dir;
    build_world(source, dir.path, o, {0, 3});
    world_build_options denser = o;
    denser.density = 3;
    std::string m = error_of([&] { build_world(source, dir.path, denser, {1, 3}); });
    EXPECT_NE(m.find("density 2"), std::string::npos) << m;
    EXPECT_NE(m.find("--density"), std::string::npos) << m;
    m = error_of([&] { build_world(source, dir.path, o, {1, 4}); });
    EXPECT_NE(m.find("shards 3"), std::string::npos) << m;
    voxel_model other = world_test_model();
    other.set({0, 0, 0}, other.get({0, 0, 0}) ? 0 : 7);
    m = error_of([&] { build_world(model_source(other), dir.path, o, {2, 3}); });
    EXPECT_NE(m.find("source_hash"), std::string::npos) << m;
    m = error_of([&] { finish_world_build(source, dir.path, denser); });
    EXPECT_NE(m.find("--density"), std::string::npos) << m;
    m = error_of([&] { build_world(source, dir.path, o, {3, 3}); });
    EXPECT_NE(m.find("shard 3 of 3 does not exist"), std::string::npos) << m;
    temp_dir empty;
    m = error_of([&] { finish_world_build(source, empty.path, o); });
    EXPECT_NE(m.find("no sharded build to finish"), std::string::npos) << m;
}

TEST(world_shards, a_shard_list_that_names_a_missing_file_is_refused) {
    voxel_model model = world_test_model();  // the source holds a pointer to it
    model_source source(model);
    world_build_options o = small_chunks();
    temp_dir dir;
    build_world(source, dir.path, o, {0, 2});
    build_world(source, dir.path, o, {1, 2});
    world_manifest listed = read_manifest_file(shard_file(dir.path, 1, 2, ".vxwm"));
    ASSERT_FALSE(listed.chunks.empty());
    fs::remove(chunk_file_path(dir.path, listed.chunks.front().key));
    std::string m = error_of([&] { finish_world_build(source, dir.path, o); });
    EXPECT_NE(m.find("it is missing: run shard 1/2 again"), std::string::npos) << m;
    build_world(source, dir.path, o, {1, 2});
    finish_world_build(source, dir.path, o);
    EXPECT_TRUE(fs::exists(manifest_path(dir.path)));
    EXPECT_FALSE(fs::exists(shards_folder(dir.path)));
}

}  // namespace
}  // namespace voxray::test
