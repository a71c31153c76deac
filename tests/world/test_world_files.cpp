// A world folder treated as untrusted input (issue 22): bad, foreign, oversized and
// resealed files are errors that name the file, or chunks reported and never shown; the
// budget is a cap; one build at a time in a folder, and a finished world is replaced
// only when asked. CPU only: these are the files and the residency manager, not a
// backend's walk.
#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>
#include <string>

#include "error_of.hpp"
#include "temp_dir.hpp"
#include "voxray/world/build/model_source.hpp"
#include "voxray/world/build/world_build.hpp"
#include "voxray/world/stream/streamed_world.hpp"
#include "world_test_model.hpp"

namespace voxray {
namespace {

namespace fs = std::filesystem;
using namespace voxray::test;

residency_options every_lod0_chunk() {
    residency_options ro;
    ro.streaming_factor = 1000.0;
    ro.budget_bytes = 1 << 30;
    return ro;
}


bool has(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

void poke32(const fs::path& file, std::streamoff at, std::uint32_t value) {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(at);
    f.write(reinterpret_cast<const char*>(&value), 4);
}
void poke64(const fs::path& file, std::streamoff at, std::uint64_t value) {
    std::fstream f(file, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(at);
    f.write(reinterpret_cast<const char*>(&value), 8);
}

chunk_key first_of_lod(const world_manifest& m, int lod) {
    for (auto& c : m.chunks)
        if (c.key.lod == lod) return c.key;
    ADD_FAILURE() << "no chunk of LOD " << lod;
    return {};
}

// Defect 2: the top LOD is always shown; a world without one of its chunks cannot open,
// and says which file and why (it said "map::at").
TEST(world_files, a_bad_top_lod_chunk_is_an_error_naming_it) {
    temp_dir built;
    build_world(model_source(world_test_model()), built.path, small_chunks());
    world_manifest m = read_manifest(built.path);
    chunk_key top = first_of_lod(m, m.grid.top_lod);
    auto top_folder = "lod" + std::to_string(m.grid.top_lod);
    struct damage {
        const char* name;
        std::function<void(const fs::path&)> apply;
        const char* problem;
    };
    std::vector<damage> cases = {
        {"missing", [&](const fs::path& d) { fs::remove(chunk_file_path(d, top)); }, "cannot read"},
        {"flipped byte", [&](const fs::path& d) { poke32(chunk_file_path(d, top), 100, 0x5a5a5a5a); }, "checksum"},
        {"newer version", [&](const fs::path& d) { poke32(chunk_file_path(d, top), 4, 2); }, "unsupported version 2"},
        {"folder deleted", [&](const fs::path& d) { fs::remove_all(d / top_folder); }, "cannot read"},
    };
    for (auto& c : cases) {
        temp_dir dir;
        fs::copy(built.path, dir.path, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
        c.apply(dir.path);
        std::string what = error_of([&] { streamed_world world(dir.path, every_lod0_chunk()); });
        EXPECT_TRUE(has(what, chunk_file_path(dir.path, top).string())) << c.name << ": " << what;
        EXPECT_TRUE(has(what, "top LOD")) << c.name << ": " << what;
        EXPECT_TRUE(has(what, c.problem)) << c.name << ": " << what;
    }
}

// Defect 3: a chunk file of another build (here: the same voxels built with other
// options, so size and voxel count agree and only the build differs) is reported, never
// shown.
TEST(world_files, a_chunk_file_of_another_build_is_reported_and_never_shown) {
    voxel_model model = world_test_model();
    temp_dir dir, other;
    build_world(model_source(model), dir.path, small_chunks());
    world_build_options denser = small_chunks();
    denser.density = 3;
    build_world(model_source(model), other.path, denser);
    world_manifest m = read_manifest(dir.path);
    chunk_key foreign = first_of_lod(m, 0);
    fs::copy_file(chunk_file_path(other.path, foreign), chunk_file_path(dir.path, foreign), fs::copy_options::overwrite_existing);
    streamed_world world(dir.path, every_lod0_chunk());
    world.update(glm::dvec3(m.bounds.min), true);
    auto errors = world.residency().errors();
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_TRUE(has(errors[0], chunk_file_path(dir.path, foreign).string())) << errors[0];
    EXPECT_TRUE(has(errors[0], "source hash")) << errors[0];
    EXPECT_EQ(world.residency().resident(foreign), nullptr);
}

// Defect 10: a chunk of the other attribute kind (an exact world given a colour-block
// chunk of the same voxels, its build hash and the manifest's size made to agree) is a
// bad chunk file like any other; the flight goes on (it aborted).
TEST(world_files, a_chunk_of_the_other_attribute_kind_is_reported_and_never_shown) {
    voxel_model model = world_test_model();
    temp_dir dir, colours;
    build_world(model_source(model), dir.path, small_chunks());
    world_build_options colour_blocks = small_chunks();
    colour_blocks.attributes = svdag_attributes::colour_blocks;
    build_world(model_source(model), colours.path, colour_blocks);
    world_manifest m = read_manifest(dir.path);
    chunk_key swapped = first_of_lod(m, 0);
    chunk_record c = read_chunk_file(chunk_file_path(colours.path, swapped));
    c.source_hash = m.source_hash;
    write_chunk_file(chunk_file_path(dir.path, swapped), c);
    for (auto& listed : m.chunks)
        if (listed.key == swapped) listed.file_bytes = fs::file_size(chunk_file_path(dir.path, swapped));
    write_manifest(dir.path, m);
    streamed_world world(dir.path, every_lod0_chunk());
    EXPECT_NO_THROW(world.update(glm::dvec3(m.bounds.min), true));
    auto errors = world.residency().errors();
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_TRUE(has(errors[0], chunk_file_path(dir.path, swapped).string())) << errors[0];
    EXPECT_TRUE(has(errors[0], "attribute kind")) << errors[0];
    EXPECT_EQ(world.residency().resident(swapped), nullptr);
}

// Defect 4: sizes are checked before anything is allocated for them. A chunk file (sparse:
// a few bytes on disk) that claims a DAG of 2^28 words for its few voxels, and a manifest
// that claims 2^25 chunks for a grid of a few cells, are refused by their header alone
// (they were read whole, 1 GiB each, and failed only at the checksum); a chunk file
// whose size the manifest does not list is refused before it is read.
TEST(world_files, sizes_are_checked_before_anything_is_allocated) {
    temp_dir dir;
    build_world(model_source(world_test_model()), dir.path, small_chunks());
    world_manifest m = read_manifest(dir.path);
    chunk_key k = first_of_lod(m, 0);
    auto chunk = chunk_file_path(dir.path, k);
    fs::path big = dir.path / "big.vxck";
    fs::copy_file(chunk, big);
    std::uint64_t words = std::uint64_t(1) << 28;
    poke64(big, chunk_file_offset::dag_words, words);
    fs::resize_file(big, chunk_file_header_bytes + 4 * words);
    std::string what = error_of([&] { read_chunk_file(big); });
    EXPECT_TRUE(has(what, "offset 64: DAG size of 268435456 words is outside")) << what;

    fs::path manifest_dir = dir.path / "sparse_manifest";
    fs::create_directories(manifest_dir);
    fs::copy_file(manifest_path(dir.path), manifest_path(manifest_dir));
    std::uint64_t claimed = std::uint64_t(1) << 25;
    poke64(manifest_path(manifest_dir), 80, claimed);
    fs::resize_file(manifest_path(manifest_dir), manifest_header_bytes + manifest_chunk_bytes * claimed);
    what = error_of([&] { read_manifest(manifest_dir); });
    EXPECT_TRUE(has(what, "offset 80: 33554432 (expected at most one chunk per cell")) << what;

    // Grown by a byte: the manifest's size says another file.
    fs::resize_file(chunk, fs::file_size(chunk) + 1);
    streamed_world world(dir.path, every_lod0_chunk());
    world.update(glm::dvec3(m.bounds.min), true);
    auto errors = world.residency().errors();
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_TRUE(has(errors[0], chunk.string() + ": " + std::to_string(fs::file_size(chunk)) + " bytes, but the manifest lists"))
        << errors[0];
}

// Defect 14: a manifest resealed (checksum made right) with fields the walk's arithmetic
// cannot take is refused, naming the offset.
TEST(world_files, a_resealed_manifest_with_unsound_fields_is_refused) {
    temp_dir dir;
    build_world(model_source(world_test_model()), dir.path, small_chunks());
    const world_manifest good = read_manifest(dir.path);
    struct damage {
        const char* name;
        std::function<void(world_manifest&)> apply;
        const char* problem;
    };
    std::vector<damage> cases = {
        {"origin off the top grid", [](world_manifest& m) { m.grid.origin.x += 1; }, "offset 16: "},
        {"far corner past INT_MAX",
         [](world_manifest& m) {
             // The last origin on the top grid below 2^31, and as many cells as make the
             // grid end at 2^31.
             m.grid.origin.y = int((std::int64_t(1) << 31) - (16 << m.grid.top_lod));
             m.grid.cells.y = 1 << m.grid.top_lod;
         },
         "a grid whose far corner fits 32 bits"},
        {"bounds past the grid", [](world_manifest& m) { m.bounds.max.z += 1 << 12; }, "offset 60: "},
        {"bounds before the grid", [](world_manifest& m) { m.bounds.min.x = m.grid.origin.x - 1; }, "offset 40: "},
        {"voxel count past the chunk", [](world_manifest& m) { m.chunks[0].voxel_count = 4097; }, "solid voxels in [1, chunk volume]"},
        {"file size of another chunk", [](world_manifest& m) { m.chunks[0].file_bytes = 3; }, "the size of a chunk file"},
    };
    for (auto& c : cases) {
        world_manifest m = good;
        c.apply(m);
        write_manifest(dir.path, m);
        std::string what = error_of([&] { read_manifest(dir.path); });
        EXPECT_TRUE(has(what, c.problem)) << c.name << ": " << what;
    }
    // A chunk count whose table size wraps around 64 bits to the file's size, resealed, in
    // a grid with cells enough to allow it: refused by the size, not allocated.
    world_manifest wide = good;
    wide.grid = {glm::ivec3(0), glm::ivec3(1 << 20), 4, 20};
    wide.bounds = {};
    write_manifest(dir.path, wide);
    std::ifstream in(manifest_path(dir.path), std::ios::binary);
    std::vector<unsigned char> b{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    in.close();
    std::uint64_t n = (std::uint64_t(1) << 59) + good.chunks.size();  // 32 n + 96 == the size, mod 2^64
    std::memcpy(b.data() + 80, &n, 8);
    fnv64 sum;
    sum.bytes(b.data(), 88);
    sum.bytes(b.data() + manifest_header_bytes, b.size() - manifest_header_bytes);
    std::memcpy(b.data() + 88, &sum.h, 8);
    std::ofstream(manifest_path(dir.path), std::ios::binary).write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
    std::string what = error_of([&] { read_manifest(dir.path); });
    EXPECT_TRUE(has(what, "offset 80: " + std::to_string(n) + " chunks do not match the file size")) << what;
}

// Defect 5: the budget is a cap. Along a path whose cuts want more than it allows, the
// resident bytes stay within it after every frame (they reached 1.7-5.9 times it), and
// a budget below the always-resident top LOD is refused with both numbers.
TEST(world_files, the_budget_caps_the_resident_bytes_along_a_path) {
    temp_dir dir;
    build_world(model_source(world_test_model()), dir.path, small_chunks());
    world_manifest m = read_manifest(dir.path);
    std::uint64_t top = m.disk_bytes(m.grid.top_lod);
    residency_options ro;
    ro.streaming_factor = 8.0;
    ro.budget_bytes = top + m.disk_bytes(0) / 5;
    streamed_world world(dir.path, ro);
    glm::dvec3 lo(m.bounds.min), hi(m.bounds.max);
    std::uint64_t skipped = 0;
    for (int f = 0; f <= 12; ++f) {
        glm::dvec3 camera = lo + (hi - lo) * (double(f) / 12.0);
        world.update(camera, f % 3 != 0);  // some frames with loads still in flight
        auto s = world.residency().stats();
        EXPECT_LE(s.resident_bytes, ro.budget_bytes) << "frame " << f;
        skipped += s.skipped_for_budget;
    }
    EXPECT_GT(skipped, 0u);  // the budget did bind
    ro.budget_bytes = top - 1;
    std::string what = error_of([&] { residency_manager r(dir.path, ro); });
    EXPECT_TRUE(has(what, "budget of " + std::to_string(top - 1) + " bytes is less than the top LOD's " + std::to_string(top)))
        << what;
}

// Defect 9: while a build holds a folder (another process: its lock is an flock on
// .voxray-build.lock), a second build into it is refused, and writes nothing.
TEST(world_files, a_second_build_into_a_busy_folder_is_refused) {
    temp_dir dir;
    int fd = ::open((dir.path / ".voxray-build.lock").c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
    std::string what = error_of([&] { build_world(model_source(world_test_model()), dir.path, small_chunks()); });
    EXPECT_TRUE(has(what, "is being built by another process")) << what;
    EXPECT_FALSE(fs::exists(dir.path / "lod0"));
    ::close(fd);
    EXPECT_NO_THROW(build_world(model_source(world_test_model()), dir.path, small_chunks()));
}

// Issue 22, "also": a folder that holds another finished world is refused unless the
// build replaces it; a replacing build leaves no chunk file its manifest does not list.
TEST(world_files, another_world_is_replaced_only_when_asked_and_leaves_no_stale_chunk) {
    temp_dir dir;
    build_world(model_source(world_test_model()), dir.path, small_chunks());
    voxel_model smaller = scenes::make_builtin("menger:27", 1);
    std::string what = error_of([&] { build_world(model_source(smaller), dir.path, small_chunks()); });
    EXPECT_TRUE(has(what, "holds another world")) << what;
    EXPECT_NO_THROW(read_manifest(dir.path));  // the old world still stands
    world_build_options replace = small_chunks();
    replace.replace = true;
    build_world(model_source(smaller), dir.path, replace);
    world_manifest m = read_manifest(dir.path);
    std::size_t files = 0;
    for (auto& e : fs::recursive_directory_iterator(dir.path))
        if (e.is_regular_file() && e.path().extension() != ".vxwm" && e.path().filename() != ".voxray-build.lock") {
            ++files;
            EXPECT_EQ(e.path().extension(), ".vxck") << e.path();
        }
    EXPECT_EQ(files, m.chunks.size());
}

// Issue 22, "also": a build reports its progress, chunk by chunk, every LOD to its end.
TEST(world_files, a_build_reports_progress_for_every_lod) {
    temp_dir dir;
    world_build_options o = small_chunks();
    std::map<int, std::pair<std::uint64_t, std::uint64_t>> last;  // lod -> (done, total)
    o.progress = [&](const world_build_progress& p) { last[p.lod] = {p.done, p.total}; };
    auto report = build_world(model_source(world_test_model()), dir.path, o);
    ASSERT_EQ(last.size(), report.lods.size());
    for (auto& [lod, counts] : last) EXPECT_EQ(counts.first, counts.second) << "LOD " << lod;
}

// Defect 8: a tiling whose cell list alone would take gigabytes is refused up front,
// with the numbers (menger:27 tiled 4096^3 grew to 2.9 GB and died on bad_alloc). (That a
// cell's voxels come from just the copies that reach it is checked, for correctness, by
// test_world_stream's a_tiled_model_is_its_copies.)
TEST(world_files, a_tiling_too_large_to_list_is_refused_with_its_numbers) {
    voxel_model menger = scenes::make_builtin("menger:27", 1);
    world_grid grid = world_grid::fit(model_source(menger, {4096, 4096, 4096}).bounds(), 8);
    std::string what = error_of([&] { model_source(menger, {4096, 4096, 4096}).cells(grid); });
    EXPECT_TRUE(has(what, "4096 x 4096 x 4096 copies of 8 model chunks are 549755813888 copy chunks")) << what;
}

}  // namespace
}  // namespace voxray
