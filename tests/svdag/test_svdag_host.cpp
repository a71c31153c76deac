// The sparse voxel DAG's builder: the same model gives the same bytes whatever the thread
// count; identical subtrees are stored once; every node's count is its voxels; the depth
// and size limits are errors with the numbers; and hits (exact materials) equal the
// reference's on models where sharing and depth-first indexing matter.
#include <gtest/gtest.h>

#include <bit>

#include "random_models.hpp"
#include "special_rays.hpp"
#include "voxray/check/compare.hpp"
#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/scenes/builtin.hpp"
#include "voxray/svdag/svdag.hpp"
#include "voxray/tracer.hpp"

namespace voxray {
namespace {

using namespace voxray::test;
using scenes::make_builtin;

svdag_options with_threads(unsigned threads) {
    svdag_options o;
    o.threads = threads;
    return o;
}

// The voxels below a node, recounted from its children (leaves: their set bits); the
// node's counts below each child after the first, against the recount of those before it.
std::uint64_t recount(std::span<const std::uint32_t> w, std::uint32_t node, int depth, int d) {
    if (d == depth - VX_SV_LEAF_EDGE_BITS) return std::uint64_t(std::popcount(w[node]) + std::popcount(w[node + 1]));
    std::uint64_t n = 0;
    int children = std::popcount(w[node] & VX_SV_NODE_MASK_BITS);
    for (int k = 0; k < children; ++k) {
        if (k > 0) {
            EXPECT_EQ(w[node + VX_SV_NODE_BELOW(children, k)], n) << "node at word " << node << ", child " << k;
        }
        n += recount(w, w[node + VX_SV_NODE_CHILDREN + k], depth, d + 1);
    }
    return n;
}

TEST(svdag, same_model_same_bytes_whatever_the_threads) {
    voxel_model model = make_builtin("terrain:96", 2);
    svdag one(model, with_threads(1)), two(model, with_threads(2)), three(model, with_threads(3));
    ASSERT_GT(one.bytes(), 0u);
    EXPECT_TRUE(std::ranges::equal(one.blob(), two.blob()));
    EXPECT_TRUE(std::ranges::equal(one.blob(), three.blob()));
}

// The same 8^3 tile everywhere, each copy with its own materials: shared geometry,
// attributes that are not.
voxel_model tiled_model(int size) {
    voxel_model tiled;
    for (int z = 0; z < size; ++z)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                if (((x * 7 + y * 3 + z * 5) & 7) < 2) tiled.set({x, y, z}, std::uint8_t(1 + (x + 2 * y + 3 * z) % 250));
    return tiled;
}

TEST(svdag, identical_subtrees_are_stored_once_and_counts_add_up) {
    voxel_model model = tiled_model(128);
    svdag dag(model);
    const svdag_stats& s = dag.stats();
    // Below the tile's size there are only a few distinct nodes; above it, one per level.
    EXPECT_GT(s.dedup_ratio(), 100.0) << s.octree_nodes << " octree nodes, " << s.dag_nodes << " DAG nodes";
    EXPECT_LT(s.dag_nodes, 40u);
    auto w = dag.blob();
    EXPECT_EQ(recount(w, w[VX_SV_HEADER_ROOT], s.depth, 0), model.voxel_count());
    EXPECT_EQ(w[VX_SV_HEADER_VOXELS], model.voxel_count());
    EXPECT_EQ(s.geometry_bytes + s.attribute_bytes, dag.bytes());
    EXPECT_EQ(s.attribute_bytes, (model.voxel_count() + 3) / 4 * 4) << "exact: one byte a voxel";
}

TEST(svdag, hits_and_materials_equal_the_reference) {
    std::vector<voxel_model> models;
    models.push_back(random_model(40, 0.3f, 7, {-21, 5, -3}));       // dense noise, off the 16-grid
    models.push_back(random_sparse({{-200, -7, 60}, {100, 90, 300}}, 20000, 8));  // a deeper cube
    models.push_back(tiled_model(64));  // shared subtrees with different materials
    models.push_back(make_builtin("menger:81", 2));
    models.push_back(random_model(8, 0.5f, 4, {16, 32, 0}));  // fits the smallest cube, 2^3
    for (auto& model : models) {
        svdag dag(model);
        dense_grid grid(model);
        auto rays = mixed_rays(model.bounds(), 20000, 3);
        std::vector<hit> got(rays.size()), expected(rays.size());
        tracer<cpu_scalar, dense_grid>(grid, cpu_options{1}).closest_hit(rays, expected);
        for (int backend = 0; backend < 2; ++backend) {
            if (backend == 0) tracer<cpu, svdag>(dag).closest_hit(rays, got);
            else tracer<cpu_scalar, svdag>(dag, cpu_options{1}).closest_hit(rays, got);
            agreement_counts c;
            for (std::size_t i = 0; i < rays.size(); ++i) {
                auto a = compare_hits(rays[i], expected[i], got[i]);
                c.add(a);
                if (a == agreement::mismatch && c.mismatches < 4)
                    ADD_FAILURE() << "ray " << i << ": expected voxel " << expected[i].voxel.x << ","
                                  << expected[i].voxel.y << "," << expected[i].voxel.z << " material "
                                  << expected[i].material << " t " << expected[i].t << ", got " << got[i].voxel.x
                                  << "," << got[i].voxel.y << "," << got[i].voxel.z << " material " << got[i].material
                                  << " t " << got[i].t << (got[i].is_hit() ? "" : " (miss)");
            }
            EXPECT_EQ(c.mismatches, 0u) << (backend == 0 ? "cpu" : "cpu-scalar");
            EXPECT_GT(c.same, c.rays / 2);
        }
    }
}

TEST(svdag, an_empty_world_is_missed_by_every_ray) {
    svdag dag{voxel_model{}};
    auto rays = mixed_rays(box3i{{0, 0, 0}, {8, 8, 8}}, 500, 5);
    std::vector<hit> hits(rays.size());
    tracer<cpu, svdag>(dag).closest_hit(rays, hits);
    for (auto& h : hits) EXPECT_FALSE(h.is_hit());
}

TEST(svdag, a_world_beyond_the_depth_limit_says_so) {
    voxel_model model;
    model.set({-100000, 0, 0}, 1);
    model.set({100000, 0, 0}, 1);
    try {
        svdag dag(model);
        FAIL() << "a 200001-voxel-wide world was accepted";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("the limit is 2^17"), std::string::npos) << e.what();
    }
}

TEST(svdag, the_blob_limit_says_so) {
    voxel_model model = random_model(32, 0.5f, 3);
    svdag_options o;
    o.max_blob_bytes = 4096;
    try {
        svdag dag(model, o);
        FAIL() << "a blob above max_blob_bytes was built";
    } catch (const std::exception& e) {
        EXPECT_NE(std::string(e.what()).find("above max_blob_bytes = 4096"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace voxray
