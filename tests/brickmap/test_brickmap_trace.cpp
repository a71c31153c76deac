// The brickmap traced on every backend against the reference (dense grid, cpu-scalar):
// built-in and shared scenes; every payload/edge variant; and after thousands of random
// region edits made from several threads, sent to each backend by incremental update().
#include <thread>

#include <gtest/gtest.h>

#include "random_models.hpp"
#include "test_data.hpp"
#include "voxray/brickmap/brickmap.hpp"
#include "voxray/check/compare.hpp"
#include "voxray/check/ray_sets.hpp"
#include "voxray/cpu.hpp"
#include "voxray/io/vox_reader.hpp"
#include "voxray/opencl.hpp"
#include "voxray/scenes/builtin.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/vulkan.hpp"

using namespace voxray;

namespace {

std::vector<hit> reference_hits(const voxel_model& model, const std::vector<ray>& rays) {
    dense_grid grid(model);
    tracer<cpu_scalar, dense_grid> t(grid);
    std::vector<hit> hits(rays.size());
    t.closest_hit(rays, hits);
    return hits;
}

template <class Tracer>
agreement_counts compare(Tracer& t, const std::vector<ray>& rays, const std::vector<hit>& expected) {
    std::vector<hit> hits(rays.size());
    t.closest_hit(rays, hits);
    agreement_counts counts;
    for (std::size_t i = 0; i < rays.size(); ++i) counts.add(compare_hits(rays[i], expected[i], hits[i]));
    return counts;
}

template <class Map>
void expect_all_backends_agree(const voxel_model& model, std::size_t count, const char* what) {
    Map map(model);
    auto rays = check_rays(model.bounds(), model.up_axis, count, 17);
    auto expected = reference_hits(model, rays);
    tracer<cpu, Map> a(map);
    tracer<cpu_scalar, Map> b(map);
    tracer<opencl, Map> c(map);
    tracer<vulkan, Map> d(map);
    for (auto counts : {compare(a, rays, expected), compare(b, rays, expected), compare(c, rays, expected),
                        compare(d, rays, expected)}) {
        EXPECT_EQ(counts.mismatches, 0u) << what;
        EXPECT_LE(counts.ties, counts.rays / 100) << what;
    }
}

TEST(brickmap_trace, builtin_scenes) {
    expect_all_backends_agree<brickmap<>>(scenes::make_builtin("menger:81"), 100000, "menger:81");
    expect_all_backends_agree<brickmap<>>(scenes::make_builtin("terrain:128"), 100000, "terrain:128");
}

TEST(brickmap_trace, payload_and_edge_variants) {
    auto model = test::random_model(37, 0.08f, 9, {-5, 3, -40});
    expect_all_backends_agree<brickmap<std::uint8_t, 4>>(model, 40000, "u8 edge 4");
    expect_all_backends_agree<brickmap<std::uint16_t, 8>>(model, 40000, "u16 edge 8");
    expect_all_backends_agree<brickmap<std::uint32_t, 16>>(model, 40000, "u32 edge 16");
    // Solid cells: a block large enough that most of its bricks collapse.
    expect_all_backends_agree<brickmap<>>(test::solid_block({-3, 0, 5}, {61, 40, 30}), 40000, "solid block");
}

TEST(brickmap_trace, shared_scenes) {
    VOXRAY_REQUIRE_DATA();
    for (auto& file : test::data_files("vox", ".vox"))
        expect_all_backends_agree<brickmap<>>(io::load_vox(file), 20000, file.filename().c_str());
}

// Random edits from 2 threads on disjoint halves of the world, then update() on every
// backend (only the dirty words travel) and the comparison with a reference model that
// received the same edits.
TEST(brickmap_trace, random_edits_from_threads_then_incremental_update) {
    auto model = scenes::make_builtin("menger:81");
    box3i world = model.bounds();
    brickmap<> map(model);
    tracer<cpu, brickmap<>> a(map);
    tracer<cpu_scalar, brickmap<>> b(map);
    tracer<opencl, brickmap<>> c(map);
    tracer<vulkan, brickmap<>> d(map);

    for (int round = 0; round < 3; ++round) {
        // Each thread edits its own half along x; the reference gets the same edits.
        struct planned { regions::sphere s; edit_op op; std::uint8_t v; };
        std::vector<planned> plans[2];
        rng g(100 + round);
        int half = world.extent().x / 2;
        for (int t = 0; t < 2; ++t)
            for (int i = 0; i < 1000; ++i) {
                int r = 1 + g.below(4);
                glm::ivec3 c(world.min.x + t * half + r + g.below(half - 2 * r), world.min.y + g.below(world.extent().y),
                             world.min.z + g.below(world.extent().z));
                plans[t].push_back({regions::sphere{c, r}, static_cast<edit_op>(g.below(3)), std::uint8_t(1 + g.below(255))});
            }
        std::thread workers[2];
        for (int t = 0; t < 2; ++t)
            workers[t] = std::thread([&, t] {
                for (auto& p : plans[t]) map.apply(p.s, p.op, p.v);
            });
        for (auto& w : workers) w.join();
        for (auto& plan : plans)
            for (auto& p : plan) {
                box3i bb = p.s.bounds();
                for (int z = std::max(bb.min.z, world.min.z); z < std::min(bb.max.z, world.max.z); ++z)
                    for (int y = std::max(bb.min.y, world.min.y); y < std::min(bb.max.y, world.max.y); ++y)
                        for (int x = std::max(bb.min.x, world.min.x); x < std::min(bb.max.x, world.max.x); ++x) {
                            glm::ivec3 q(x, y, z);
                            if (!p.s.contains(q)) continue;
                            if (p.op == edit_op::fill) model.set(q, p.v);
                            else if (p.op == edit_op::erase) model.set(q, 0);
                            else if (model.get(q)) model.set(q, p.v);
                        }
            }

        auto ranges = map.take_dirty_ranges();
        std::uint64_t dirty_words = 0;
        for (auto& r : ranges) dirty_words += r.count;
        a.update(map, ranges);
        b.update(map, ranges);
        c.update(map, ranges);
        d.update(map, ranges);
        if (dirty_words < map.blob().size()) {
            EXPECT_LT(c.bytes_uploaded_last_update(), map.bytes()) << "round " << round << ": not incremental";
            EXPECT_LT(d.bytes_uploaded_last_update(), map.bytes()) << "round " << round << ": not incremental";
        }

        auto rays = check_rays(world, model.up_axis, 60000, 50 + round);
        auto expected = reference_hits(model, rays);
        for (auto counts : {compare(a, rays, expected), compare(b, rays, expected), compare(c, rays, expected),
                            compare(d, rays, expected)})
            EXPECT_EQ(counts.mismatches, 0u) << "round " << round;
    }
}

// A one-voxel edit in a 4096^3 world travels as about one brick.
TEST(brickmap_trace, one_voxel_edit_uploads_about_one_brick) {
    brickmap<> map(box3i{{0, 0, 0}, {4096, 4096, 4096}});
    map.fill_box({{100, 100, 100}, {164, 110, 164}}, 3);
    tracer<opencl, brickmap<>> c(map);
    tracer<vulkan, brickmap<>> d(map);
    (void)map.take_dirty_ranges();
    map.set({120, 110, 120}, 9);  // a new voxel on top of the slab: a new brick
    auto ranges = map.take_dirty_ranges();
    c.update(map, ranges);
    d.update(map, ranges);
    std::uint64_t brick_bytes = 144 * 4;
    EXPECT_LE(c.bytes_uploaded_last_update(), 2 * brick_bytes);
    EXPECT_LE(d.bytes_uploaded_last_update(), 2 * brick_bytes);
    ray r{{120.5f, 200.0f, 120.5f}, 0.0f, {0.0f, -1.0f, 0.0f}, INFINITY};
    hit h;
    d.closest_hit({&r, 1}, {&h, 1});
    EXPECT_TRUE(h.is_hit());
    EXPECT_EQ(h.voxel, glm::ivec3(120, 110, 120));
    EXPECT_EQ(h.material, 9u);
}

}  // namespace
