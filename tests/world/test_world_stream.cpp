// A world built out of core into chunk files, and streamed back: the build equals the
// in-memory chunked_world chunk for chunk (whatever the thread count, and after an
// interrupted build resumes); LOD selection follows Equation 1; the residency manager
// keeps its budget, loads coarse first and evicts; a corrupt file is reported and never
// shown; and what rays see through the streamed world is, on every backend, bit for bit
// what the in-memory world shows for the same cut, sent to the backend incrementally.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <unistd.h>

#include "hit_bits.hpp"
#include "random_models.hpp"
#include "temp_dir.hpp"
#include "special_rays.hpp"
#include "test_data.hpp"
#include "voxray/check/compare.hpp"
#include "voxray/cpu.hpp"
#include "voxray/generated/backends.hpp"
#include "voxray/io/mesh_loader.hpp"
#include "voxray/tracer.hpp"
#include "voxray/world/build/mesh_source.hpp"
#include "voxray/world/build/model_source.hpp"
#include "voxray/world/stream/streamed_world.hpp"
#include "voxray/world/build/world_build.hpp"
#include "every_backend.hpp"
#include "world_test_model.hpp"

namespace voxray {
namespace {

namespace fs = std::filesystem;
using namespace voxray::test;

// Streaming that never runs out of budget: what is shown follows Equation 1 alone.
residency_options roomy_residency() {
    residency_options o;
    o.streaming_factor = 1.5;
    o.budget_bytes = 1 << 30;
    return o;
}

std::vector<char> bytes_of(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(world_build, equals_the_in_memory_world_on_any_thread_count) {
    voxel_model model = world_test_model();
    world_options mo;
    mo.chunk_bits = 4;
    chunked_world memory(model, mo);
    temp_dir one, two;
    auto r1 = build_world(model_source(model), one.path, small_chunks(1));
    auto r2 = build_world(model_source(model), two.path, small_chunks(2));
    world_manifest m = read_manifest(one.path);
    EXPECT_EQ(m.grid.top_lod, memory.grid().top_lod);
    EXPECT_EQ(m.grid.origin, memory.grid().origin);
    ASSERT_EQ(r1.lods.size(), std::size_t(m.grid.top_lod) + 1);
    std::size_t compared = 0;
    for (int lod = 0; lod <= m.grid.top_lod; ++lod) {
        EXPECT_EQ(r1.lods[std::size_t(lod)].chunks, memory.stats().chunks[std::size_t(lod)]) << "LOD " << lod;
        EXPECT_EQ(r1.lods[std::size_t(lod)].voxels, memory.stats().voxels[std::size_t(lod)]) << "LOD " << lod;
    }
    EXPECT_EQ(r1.lods[0].voxels, model.voxel_count());
    for (auto& c : m.chunks) {
        chunk_record disk = read_chunk_file(chunk_file_path(one.path, c.key), 4);
        const chunk_record* mem = memory.find(c.key);
        ASSERT_NE(mem, nullptr);
        EXPECT_EQ(disk.dag, mem->dag);
        EXPECT_EQ(disk.solid_min, mem->solid_min);
        EXPECT_EQ(disk.solid_max, mem->solid_max);
        EXPECT_EQ(bytes_of(chunk_file_path(one.path, c.key)), bytes_of(chunk_file_path(two.path, c.key)));
        ++compared;
    }
    EXPECT_EQ(compared, [&] {
        std::size_t n = 0;
        for (auto x : memory.stats().chunks) n += x;
        return n;
    }());
    EXPECT_EQ(bytes_of(manifest_path(one.path)), bytes_of(manifest_path(two.path)));
    EXPECT_GT(r2.voxels_per_second(), 0.0);
}

TEST(world_build, resumes_an_interrupted_build_and_rebuilds_what_is_missing_or_corrupt) {
    voxel_model model = world_test_model();
    temp_dir dir;
    build_world(model_source(model), dir.path, small_chunks());
    world_manifest first = read_manifest(dir.path);
    auto manifest_bytes = bytes_of(manifest_path(dir.path));
    // An interruption: the manifest never written, one file missing, one half written.
    fs::remove(manifest_path(dir.path));
    fs::remove(chunk_file_path(dir.path, first.chunks[3].key));
    fs::resize_file(chunk_file_path(dir.path, first.chunks[10].key), 50);
    EXPECT_THROW(read_manifest(dir.path), error);
    // The same voxels in a model filled in another order: the same source.
    voxel_model same;
    std::vector<std::pair<glm::ivec3, std::uint8_t>> voxels;
    model.for_each_voxel([&](glm::ivec3 p, std::uint8_t v) { voxels.emplace_back(p, v); });
    for (auto it = voxels.rbegin(); it != voxels.rend(); ++it) same.set(it->first, it->second);
    same.palette() = model.palette();
    auto again = build_world(model_source(same), dir.path, small_chunks());
    std::uint64_t resumed = 0, total = 0;
    for (auto& l : again.lods) resumed += l.resumed, total += l.chunks;
    EXPECT_EQ(total, first.chunks.size());
    EXPECT_EQ(resumed, total - 2);
    EXPECT_EQ(bytes_of(manifest_path(dir.path)), manifest_bytes);
    // Other options are another build: nothing is kept.
    world_build_options other = small_chunks();
    other.density = 3;
    other.replace = true;  // (refused otherwise: test_world_files)
    auto third = build_world(model_source(model), dir.path, other);
    for (auto& l : third.lods) EXPECT_EQ(l.resumed, 0u);
}

TEST(world_build, a_tiled_model_is_its_copies) {
    voxel_model model = random_model(24, 0.2f, 8, glm::ivec3(-5, 3, 0));
    temp_dir dir;
    auto report = build_world(model_source(model, {3, 1, 2}), dir.path, small_chunks());
    EXPECT_EQ(report.lods[0].voxels, 6 * model.voxel_count());
    world_manifest m = read_manifest(dir.path);
    EXPECT_EQ(m.bounds.extent(), model.bounds().extent() * glm::ivec3(3, 1, 2));
    EXPECT_THROW(model_source(model, {0, 1, 1}), error);
}

// Out of core from a mesh, chunk by chunk: the same chunks as the in-memory world of the
// whole-model voxelization (so the same voxels and colours, at every LOD).
TEST(world_build, a_mesh_builds_chunk_by_chunk_what_the_voxelizer_makes) {
    VOXRAY_REQUIRE_DATA();
    for (const char* name : {"stanford_bunny.ply", "dabrovic_sponza.obj"}) {
        SCOPED_TRACE(name);
        io::triangle_mesh mesh = io::load_mesh(*data_dir() / "mesh" / name);
        io::voxelize_options vo;
        vo.resolution = 160;
        voxel_model whole = io::voxelize(mesh, vo);
        world_options mo;
        mo.chunk_bits = 5;
        chunked_world memory(whole, mo);
        temp_dir dir;
        world_build_options o = small_chunks();
        o.chunk_bits = 5;
        auto report = build_world(mesh_source(mesh, 160), dir.path, o);
        EXPECT_EQ(report.lods[0].voxels, whole.voxel_count());
        world_manifest m = read_manifest(dir.path);
        std::size_t total = 0;
        for (auto x : memory.stats().chunks) total += x;
        ASSERT_EQ(m.chunks.size(), total);
        for (auto& c : m.chunks) {
            const chunk_record* mem = memory.find(c.key);
            ASSERT_NE(mem, nullptr);
            EXPECT_EQ(read_chunk_file(chunk_file_path(dir.path, c.key), 5).dag, mem->dag) << "LOD " << c.key.lod;
        }
    }
    io::triangle_mesh empty;
    EXPECT_THROW(mesh_source(empty, 64), error);
}

TEST(world_lod_select, equation_1_splits_near_regions_and_keeps_far_ones_coarse) {
    voxel_model model = world_test_model();
    temp_dir dir;
    build_world(model_source(model), dir.path, small_chunks());
    world_manifest m = read_manifest(dir.path);
    lod_tree tree(m);
    glm::dvec3 camera = glm::dvec3(m.bounds.min) + glm::dvec3(2, 2, 40);
    for (double factor : {0.5, 1.2, 2.0, 4.0}) {
        auto cut = tree.select(camera, factor);
        ASSERT_FALSE(cut.empty());
        for (auto& c : cut) {
            double size = double(16 << c.key.lod);
            double distance = glm::length(tree.centre(c.key) - camera);
            EXPECT_NEAR(c.distance, distance, 1e-9);
            // Chosen: LOD 0, or a region Equation 1 does not split.
            EXPECT_TRUE(c.key.lod == 0 || size * factor - distance <= 0) << "LOD " << c.key.lod;
            // Its parent was split (else the parent would stand instead).
            if (c.key.lod < m.grid.top_lod) {
                chunk_key parent{c.key.lod + 1, c.key.cell >> 1};
                EXPECT_GT(double(16 << parent.lod) * factor - glm::length(tree.centre(parent) - camera), 0);
            }
        }
        // Coarse first, nearer first within a LOD.
        for (std::size_t i = 1; i < cut.size(); ++i)
            EXPECT_TRUE(cut[i - 1].key.lod > cut[i].key.lod ||
                        (cut[i - 1].key.lod == cut[i].key.lod && cut[i - 1].distance <= cut[i].distance));
    }
    EXPECT_LT(tree.select(camera, 0.5).size(), tree.select(camera, 4.0).size());
    EXPECT_THROW(tree.select(camera, 0.0), error);
}

template <class Backend>
void streamed_matches_memory(const char* backend) {
    SCOPED_TRACE(backend);
    voxel_model model = world_test_model();
    temp_dir dir;
    build_world(model_source(model), dir.path, small_chunks());
    world_options mo;
    mo.chunk_bits = 4;
    chunked_world memory(model, mo);

    streamed_world world(dir.path, roomy_residency());
    tracer<Backend, streamed_world> streamed(world);
    auto rays = mixed_rays(model.bounds(), 3000, 17);
    std::vector<hit> got(rays.size()), expected(rays.size());
    box3i b = model.bounds();
    // A camera path across the world: each frame, the streamed world against the
    // in-memory world showing the same placements.
    for (int frame = 0; frame < 4; ++frame) {
        glm::dvec3 camera = glm::dvec3(b.min) + glm::dvec3(b.extent()) * glm::dvec3(0.1 + 0.27 * frame, 0.5, 1.2);
        world.update(camera, true);
        std::uint64_t blob_bytes = world.bytes();
        streamed.update(world);
        if (frame > 0) {
            EXPECT_LT(streamed.bytes_uploaded_last_update(), blob_bytes) << "frame " << frame << ": not incremental";
        }
        auto cut = world.residency().placements();
        std::vector<placement> same;
        for (auto& p : cut) same.push_back({p.key, memory.find(p.key)});
        chunked_world shown = memory;
        shown.show(same);
        tracer<cpu_scalar, chunked_world>(shown, cpu_options{1}).closest_hit(rays, expected);
        streamed.closest_hit(rays, got);
        std::size_t differ = 0, hits = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            differ += !same_bits(got[i], expected[i]);
            hits += got[i].is_hit();
        }
        EXPECT_EQ(differ, 0u) << "frame " << frame;
        EXPECT_GT(hits, rays.size() / 5);
        auto s = world.residency().stats();
        EXPECT_EQ(s.failures, 0u);
        std::printf("[%s] frame %d: %llu chunks shown, %llu resident (%llu bytes), %llu loads, %llu evictions, sent %llu of %llu bytes\n",
                    backend, frame, (unsigned long long)world.shown_chunks(), (unsigned long long)s.resident_chunks,
                    (unsigned long long)s.resident_bytes, (unsigned long long)s.loads, (unsigned long long)s.evictions,
                    (unsigned long long)streamed.bytes_uploaded_last_update(), (unsigned long long)blob_bytes);
    }
    EXPECT_GT(world.residency().stats().evictions, 0u);
}

template <class Backend>
struct world_stream_on : ::testing::Test {};
TYPED_TEST_SUITE(world_stream_on, every_backend, backend_names);

TYPED_TEST(world_stream_on, matches_the_in_memory_world) { streamed_matches_memory<TypeParam>(TypeParam::name); }

// Several tracers on one streamed world, one per backend, each refreshed with
// update(world) after every frame, from threads of their own: each must hold the world's
// current blob and trace what a tracer made from scratch sees. (Handing the changed words to whichever tracer asked
// first left the others with a new directory over an old DAG pool.)
TEST(world_stream, every_tracer_of_one_world_stays_exact) {
    voxel_model model = world_test_model();
    temp_dir dir;
    build_world(model_source(model), dir.path, small_chunks());
    streamed_world world(dir.path, roomy_residency());
    auto rays = mixed_rays(model.bounds(), 3000, 23);
    std::vector<hit> expected(rays.size());
    // One tracer per linked backend; each frame: update, check the blob it holds, trace.
    std::vector<std::function<void(int)>> frames;
    for_each_type(registered::backends{}, [&]<class B>() {
        auto t = std::make_shared<tracer<B, streamed_world>>(world);
        frames.push_back([t, &world, &rays, &expected](int frame) {
            t->update(world);
            auto held = t->engine().download_blob();
            auto blob = world.blob();
            // A stale blob is reported here, before any ray walks it.
            ASSERT_TRUE(held.size() >= blob.size() && std::equal(blob.begin(), blob.end(), held.begin()))
                << B::name << ", frame " << frame << ": the tracer holds another blob than the world";
            std::vector<hit> got(rays.size());
            t->closest_hit(rays, got);
            std::size_t differ = 0;
            for (std::size_t i = 0; i < rays.size(); ++i) differ += !same_bits(got[i], expected[i]);
            EXPECT_EQ(differ, 0u) << B::name << ", frame " << frame;
        });
    });
    ASSERT_GE(frames.size(), 2u);
    box3i b = model.bounds();
    for (int frame = 0; frame < 6; ++frame) {
        glm::dvec3 camera = glm::dvec3(b.min) + glm::dvec3(b.extent()) * glm::dvec3(0.1 + 0.18 * frame, 0.5, 1.2);
        world.update(camera, true);
        tracer<cpu_scalar, streamed_world>(world, cpu_options{1}).closest_hit(rays, expected);  // from scratch
        // Each tracer updates and traces on a thread of its own, all at once.
        std::vector<std::thread> threads;
        for (auto& f : frames) threads.emplace_back(f, frame);
        for (auto& t : threads) t.join();
    }
    EXPECT_GT(world.residency().stats().evictions, 0u);
}

TEST(world_stream, the_budget_holds_and_the_coarse_lods_come_first) {
    voxel_model model = world_test_model();
    temp_dir dir;
    build_world(model_source(model), dir.path, small_chunks());
    world_manifest m = read_manifest(dir.path);
    std::uint64_t top = 0;
    for (auto& c : m.chunks)
        if (c.key.lod == m.grid.top_lod) top += c.file_bytes;
    residency_options ro;
    ro.streaming_factor = 8.0;  // wants every LOD 0 chunk near the camera...
    ro.budget_bytes = top + m.disk_bytes(0) / 4;  // ...but a quarter of them fit
    residency_manager r(dir.path, ro);
    glm::dvec3 camera = glm::dvec3(m.bounds.min);
    r.request(camera);
    r.wait_for_loads();
    r.commit();
    auto s = r.stats();
    EXPECT_LE(s.resident_bytes, ro.budget_bytes);
    EXPECT_GT(s.skipped_for_budget, 0u);
    // Stand-ins cover what the budget left out: every wanted region has a placement.
    EXPECT_FALSE(r.placements().empty());
    // Nearer chunks were preferred: every resident LOD 0 chunk is no farther than every
    // LOD 0 chunk left out.
    lod_tree tree(m);
    double farthest_in = 0, nearest_out = 1e30;
    for (auto& c : tree.select(camera, ro.streaming_factor)) {
        if (c.key.lod != 0) continue;
        if (r.resident(c.key))
            farthest_in = std::max(farthest_in, c.distance);
        else
            nearest_out = std::min(nearest_out, c.distance);
    }
    EXPECT_LE(farthest_in, nearest_out);
}

TEST(world_stream, a_corrupt_chunk_file_is_reported_and_never_shown) {
    voxel_model model = world_test_model();
    temp_dir dir;
    build_world(model_source(model), dir.path, small_chunks());
    world_manifest m = read_manifest(dir.path);
    chunk_key bad = m.chunks.front().key;  // LOD 0
    ASSERT_EQ(bad.lod, 0);
    {
        std::fstream f(chunk_file_path(dir.path, bad), std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(200);
        f.put('\x5a');
    }
    residency_options ro;
    ro.streaming_factor = 1000.0;  // every LOD 0 chunk
    ro.budget_bytes = 1 << 30;
    streamed_world world(dir.path, ro);
    world.update(glm::dvec3(m.bounds.min), true);
    auto errors = world.residency().errors();
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find(chunk_file_path(dir.path, bad).string()), std::string::npos) << errors[0];
    EXPECT_EQ(world.residency().resident(bad), nullptr);
    // Its region is shown through a coarser chunk; every other one at LOD 0.
    bool stand_in = false;
    for (auto& p : world.residency().placements()) {
        EXPECT_FALSE(p.key == bad);
        stand_in = stand_in || (p.key.lod > 0 && (bad.cell >> p.key.lod) == p.key.cell);
    }
    EXPECT_TRUE(stand_in);
}

TEST(world_stream, rays_see_nothing_new_until_update) {
    voxel_model model = world_test_model();
    temp_dir dir;
    build_world(model_source(model), dir.path, small_chunks());
    residency_options ro;
    ro.streaming_factor = 1000.0;
    streamed_world world(dir.path, ro);
    std::vector<std::uint32_t> before(world.blob().begin(), world.blob().end());
    world.residency().request(glm::dvec3(model.bounds().min));
    world.residency().wait_for_loads();  // loaded, not committed
    EXPECT_TRUE(std::equal(before.begin(), before.end(), world.blob().begin(), world.blob().end()));
    EXPECT_TRUE(world.update(glm::dvec3(model.bounds().min), true));
    EXPECT_GT(world.shown_chunks(), read_manifest(dir.path).chunks.size() / 2);
}

TEST(world_stream, a_folder_without_a_manifest_is_an_error_naming_it) {
    temp_dir dir;
    fs::create_directories(dir.path);
    try {
        streamed_world world(dir.path);
        FAIL() << "no error";
    } catch (const error& e) {
        EXPECT_NE(std::string(e.what()).find("world.vxwm"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace voxray
