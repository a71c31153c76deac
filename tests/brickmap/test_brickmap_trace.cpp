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
#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#if VOXRAY_WITH_OPENCL
#include "voxray/opencl.hpp"
#endif
#if VOXRAY_WITH_VULKAN
#include "voxray/vulkan.hpp"
#endif

using namespace voxray;

namespace {

using backends = type_list<cpu, cpu_scalar
#if VOXRAY_WITH_OPENCL
                           , opencl
#endif
#if VOXRAY_WITH_VULKAN
                           , vulkan
#endif
                           >;

template <class Tracer>
std::vector<hit> closest(Tracer& t, const std::vector<ray>& rays) {
    std::vector<hit> hits(rays.size());
    t.closest_hit(rays, hits);
    return hits;
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
        auto hits = closest(t, rays);
        agreement_counts counts;
        std::size_t different = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            counts.add(compare_hits(rays[i], expected[i], hits[i]));
            different += !test::same_bits(same_map[i], hits[i]);
        }
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

}  // namespace
