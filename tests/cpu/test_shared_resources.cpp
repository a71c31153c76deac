// CPU tracers sharing resources: one thread pool for several tracers (used from several
// threads at once), and tracing a structure's blob in place (cpu_options::borrow_blob)
// instead of a copy. Each must give the hits of a tracer with its own pool and copy.
#include <memory>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "hit_bits.hpp"
#include "random_models.hpp"
#include "voxray/brickmap/brickmap.hpp"
#include "voxray/check/ray_sets.hpp"
#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"

using namespace voxray;

namespace {

template <class Tracer>
std::vector<hit> trace(Tracer& t, const std::vector<ray>& rays) {
    std::vector<hit> hits(rays.size());
    t.closest_hit(rays, hits);
    return hits;
}

std::size_t differences(const std::vector<hit>& a, const std::vector<hit>& b) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) n += !test::identical(a[i], b[i]);
    return n;
}

TEST(SharedResources, TracersShareOnePool) {
    voxel_model model = test::random_model(32, 0.05f, 3);
    dense_grid grid(model);
    brickmap<> map(model);
    auto rays = check_rays(model.bounds(), 1, 20000, 4);
    tracer<cpu, dense_grid> own_grid(grid);
    tracer<cpu, brickmap<>> own_map(map);
    auto expected_grid = trace(own_grid, rays), expected_map = trace(own_map, rays);

    auto pool = std::make_shared<cpu_thread_pool>(3);
    tracer<cpu, dense_grid> a(grid, {.pool = pool});
    tracer<cpu, brickmap<>> b(map, {.pool = pool});
    EXPECT_EQ(a.engine().pool(), pool);
    EXPECT_EQ(b.engine().pool(), pool);
    EXPECT_EQ(a.engine().threads(), 3u);
    // Both tracers, from two threads at once, on the one pool.
    std::vector<hit> got_grid, got_map;
    std::thread other([&] { for (int k = 0; k < 5; ++k) got_map = trace(b, rays); });
    for (int k = 0; k < 5; ++k) got_grid = trace(a, rays);
    other.join();
    EXPECT_EQ(differences(got_grid, expected_grid), 0u);
    EXPECT_EQ(differences(got_map, expected_map), 0u);
}

TEST(SharedResources, BorrowedBlobIsTracedInPlace) {
    voxel_model model = test::random_model(32, 0.05f, 8);
    brickmap<> map(model);
    auto rays = check_rays(model.bounds(), 1, 20000, 9);
    tracer<cpu, brickmap<>> copied(map);
    tracer<cpu, brickmap<>> borrowed(map, {.borrow_blob = true});
    EXPECT_GT(copied.bytes_uploaded_last_update(), 0u);
    EXPECT_EQ(borrowed.bytes_uploaded_last_update(), 0u) << "borrowing copies nothing";
    EXPECT_EQ(differences(trace(borrowed, rays), trace(copied, rays)), 0u);

    // After an edit and update(), the borrowed tracer sees the structure's words again
    // (re-pointed, nothing copied) and agrees with the copying tracer.
    map.fill_sphere({16, 16, 16}, 9, 77);
    copied.update(map);
    borrowed.update(map);
    EXPECT_EQ(borrowed.bytes_uploaded_last_update(), 0u);
    auto after = trace(borrowed, rays);
    EXPECT_EQ(differences(after, trace(copied, rays)), 0u);
    std::size_t on_sphere = 0;
    for (const hit& h : after) on_sphere += h.is_hit() && h.material == 77;
    EXPECT_GT(on_sphere, 0u) << "the edit is not visible to the borrowed tracer";
}

}  // namespace
