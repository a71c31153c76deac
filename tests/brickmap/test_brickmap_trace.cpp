// Brickmap variants the registered brickmap<> (covered by tests/conformance) does not
// reach: every payload width and brick edge traced on every backend built, against the
// reference (dense grid, cpu_scalar) and bit for bit against cpu_scalar; and a one-voxel
// edit in a 4096^3 world that travels to a device as about one brick.
#include <tuple>
#include <utility>

#include <gtest/gtest.h>

#include "hit_bits.hpp"
#include "random_models.hpp"
#include "voxray/brickmap/brickmap.hpp"
#include "voxray/check/compare.hpp"
#include "voxray/check/ray_sets.hpp"
#include "voxray/core/type_list.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/generated/backends.hpp"

using namespace voxray;

namespace {

// Every tracer backend this program links.
using backends = registered::backends;

template <class Tracer>
std::vector<hit> closest(Tracer& t, const std::vector<ray>& rays) {
    std::vector<hit> hits(rays.size());
    t.closest_hit(rays, hits);
    return hits;
}

// Hits against the reference (agreement counts) and, bit for bit, against `same_map`.
std::pair<agreement_counts, std::size_t> disagreements(const std::vector<ray>& rays, const std::vector<hit>& expected,
                                                       const std::vector<hit>& same_map, const std::vector<hit>& hits) {
    agreement_counts counts;
    std::size_t different = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        counts.add(compare_hits(rays[i], expected[i], hits[i]));
        different += !test::same_bits(same_map[i], hits[i]);
    }
    return {counts, different};
}

template <class Map>
void expect_all_backends_agree(const voxel_model& model, std::size_t count, const char* what) {
    Map map(model);
    auto rays = check_rays(model.bounds(), model.up_axis, count, 17);
    dense_grid grid(model);
    tracer<cpu_scalar, dense_grid> reference(grid, cpu_options{1});
    tracer<cpu_scalar, Map> scalar(map, cpu_options{1});
    auto expected = closest(reference, rays), same_map = closest(scalar, rays);
    for_each_type(backends{}, [&]<class B>() {
        tracer<B, Map> t(map);
        auto [counts, different] = disagreements(rays, expected, same_map, closest(t, rays));
        EXPECT_EQ(counts.mismatches, 0u) << what << " on " << B::name;
        EXPECT_LE(counts.ties, counts.rays / 100) << what << " on " << B::name;
        EXPECT_EQ(different, 0u) << what << " on " << B::name << ": not bit-identical to cpu_scalar";
    });
}

TEST(brickmap_trace, payload_and_edge_variants) {
    auto model = test::random_model(37, 0.08f, 9, {-5, 3, -40});
    expect_all_backends_agree<brickmap<std::uint8_t, 4>>(model, 40000, "u8 edge 4");
    expect_all_backends_agree<brickmap<std::uint16_t, 8>>(model, 40000, "u16 edge 8");
    expect_all_backends_agree<brickmap<std::uint32_t, 16>>(model, 40000, "u32 edge 16");
    // Solid cells: a block large enough that most of its bricks collapse.
    auto block = test::solid_block({-3, 0, 5}, {61, 40, 30});
    expect_all_backends_agree<brickmap<std::uint8_t, 4>>(block, 40000, "solid block, edge 4");
    expect_all_backends_agree<brickmap<std::uint32_t, 16>>(block, 40000, "solid block, edge 16");
}

// A one-voxel edit in a 4096^3 world travels as about one brick to tracers made before
// it, and is then traced.
template <class... B>
void one_voxel_edit(type_list<B...>) {
    brickmap<> map(box3i{{0, 0, 0}, {4096, 4096, 4096}});
    map.fill_box({{100, 100, 100}, {164, 110, 164}}, 3);
    (void)map.take_dirty_ranges();
    std::tuple<tracer<B, brickmap<>>...> tracers{((void)sizeof(B), std::as_const(map))...};
    map.set({120, 110, 120}, 9);  // a new voxel on top of the slab: a new brick
    auto ranges = map.take_dirty_ranges();
    std::apply([&](auto&... t) { (t.update(map, ranges), ...); }, tracers);
    auto check = [&](auto& t, const char* name) {
        std::uint64_t brick_bytes = 144 * 4;
        EXPECT_LE(t.bytes_uploaded_last_update(), 2 * brick_bytes) << name;
        ray r{{120.5f, 200.0f, 120.5f}, 0.0f, {0.0f, -1.0f, 0.0f}, INFINITY};
        hit h;
        t.closest_hit({&r, 1}, {&h, 1});
        EXPECT_TRUE(h.is_hit()) << name;
        EXPECT_EQ(h.voxel, glm::ivec3(120, 110, 120)) << name;
        EXPECT_EQ(h.material, 9u) << name;
    };
    (check(std::get<tracer<B, brickmap<>>>(tracers), B::name), ...);
}

TEST(brickmap_trace, one_voxel_edit_uploads_about_one_brick) { one_voxel_edit(backends{}); }

// Fills outside the world grow it (its min corner moves down by whole pages, its max up);
// tracers made before then receive the re-laid-out blob through update() and trace the
// grown world like a dense grid of the same voxels, bit for bit like a fresh tracer.
template <class... B>
void grown_world_update(type_list<B...>) {
    auto model = test::random_model(37, 0.08f, 9, {-5, 3, -40});
    brickmap<> map(model);
    std::tuple<tracer<B, brickmap<>>...> tracers{((void)sizeof(B), std::as_const(map))...};
    box3i before = map.bounds();
    regions::sphere below{before.min - 20, 6}, above{before.max + glm::ivec3(30, 2, 9), 5};
    map.fill_sphere(below.centre, below.radius, 9);
    map.fill_sphere(above.centre, above.radius, 11);
    ASSERT_LT(map.bounds().min.x, before.min.x);
    ASSERT_GT(map.bounds().max.x, before.max.x);
    for (const auto& s : {below, above}) {
        box3i b = s.bounds();
        for (int z = b.min.z; z < b.max.z; ++z)
            for (int y = b.min.y; y < b.max.y; ++y)
                for (int x = b.min.x; x < b.max.x; ++x)
                    if (s.contains({x, y, z})) model.set({x, y, z}, s.radius == 6 ? 9 : 11);
    }
    auto ranges = map.take_dirty_ranges();
    std::apply([&](auto&... t) { (t.update(map, ranges), ...); }, tracers);
    auto rays = check_rays(map.bounds(), model.up_axis, 30000, 23);
    dense_grid grid(model);
    tracer<cpu_scalar, dense_grid> reference(grid, cpu_options{1});
    tracer<cpu_scalar, brickmap<>> fresh(map, cpu_options{1});
    auto expected = closest(reference, rays), same_map = closest(fresh, rays);
    std::size_t on_spheres = 0;
    for (auto& h : expected) on_spheres += h.is_hit() && (h.material == 9 || h.material == 11);
    EXPECT_GT(on_spheres, 20u);
    auto check = [&](auto& t, const char* name) {
        EXPECT_EQ(t.bytes_uploaded_last_update(), map.bytes()) << name;
        auto [counts, different] = disagreements(rays, expected, same_map, closest(t, rays));
        EXPECT_EQ(counts.mismatches, 0u) << name;
        EXPECT_EQ(different, 0u) << name << ": not bit-identical to a fresh cpu_scalar tracer";
    };
    (check(std::get<tracer<B, brickmap<>>>(tracers), B::name), ...);
}

// The first update after a build and a tracer's construction sends only what changed:
// an edit in an existing brick, then a first new brick (build left headroom in the pool),
// each about one brick; a tracer made between two edits receives only the second, an
// older one both; every device ends equal to the host.
template <class... B>
void first_updates_send_only_changes(type_list<B...>) {
    voxel_model model;
    for (int i = 0; i < 40; ++i) model.set({3 * i % 100, 7 + i % 5, 11 * i % 90}, std::uint8_t(1 + i));
    auto map = brickmap<>::build(model);
    std::tuple<tracer<B, brickmap<>>...> early{((void)sizeof(B), std::as_const(map))...};
    constexpr std::uint64_t brick_bytes = 144 * 4;
    auto expect_small = [&](auto& t, const char* name, const char* what) {
        EXPECT_LE(t.bytes_uploaded_last_update(), 2 * brick_bytes) << name << ": " << what << " of a "
                                                                    << map.bytes() << "-byte blob";
    };
    auto expect_device_equals_host = [&](auto& t, const char* name) {
        auto host = std::vector<std::uint32_t>(map.blob().begin(), map.blob().end());
        EXPECT_TRUE(t.engine().download_blob() == host) << name;
    };
    map.set({3, 8, 11}, 200);  // voxel 1 of the model: an existing brick
    std::apply([&](auto&... t) { (t.update(map), ...); }, early);
    (expect_small(std::get<tracer<B, brickmap<>>>(early), B::name, "edit in a brick"), ...);
    std::size_t words = map.blob().size();
    map.set({90, 9, 30}, 201);  // an empty brick inside the world: a new brick
    ASSERT_EQ(map.blob().size(), words) << "build() left no headroom";
    std::tuple<tracer<B, brickmap<>>...> late{((void)sizeof(B), std::as_const(map))...};
    std::apply([&](auto&... t) { (t.update(map), ...); }, early);
    (expect_small(std::get<tracer<B, brickmap<>>>(early), B::name, "first new brick"), ...);
    map.set({91, 9, 30}, 202);
    std::apply([&](auto&... t) { (t.update(map), ...); }, late);
    std::apply([&](auto&... t) { (t.update(map), ...); }, early);
    (expect_small(std::get<tracer<B, brickmap<>>>(late), B::name, "edit after construction"), ...);
    (expect_device_equals_host(std::get<tracer<B, brickmap<>>>(early), B::name), ...);
    (expect_device_equals_host(std::get<tracer<B, brickmap<>>>(late), B::name), ...);
}

TEST(brickmap_trace, first_updates_send_only_changes) { first_updates_send_only_changes(backends{}); }

TEST(brickmap_trace, grown_world_reaches_every_backend) { grown_world_update(backends{}); }

}  // namespace
