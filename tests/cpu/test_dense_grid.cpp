// The reference grid's own limits (its traversal is checked by tests/conformance).
#include <gtest/gtest.h>

#include "voxray/core/error.hpp"
#include "voxray/dense_grid/dense_grid.hpp"

using namespace voxray;

TEST(dense_grid, rejects_a_chunk_table_over_the_limit) {
    voxel_model m;
    m.set({0, 0, 0}, 1);
    m.set({(1 << 20) - 1, (1 << 20) - 1, 4000}, 1);
    EXPECT_THROW(dense_grid{m}, voxray::error);
}

TEST(dense_grid, counts_and_bounds_its_voxels) {
    voxel_model m;
    m.set({-3, 4, 17}, 1);
    m.set({5, -2, 0}, 9);
    dense_grid grid(m);
    EXPECT_EQ(grid.voxel_count(), 2u);
    EXPECT_EQ(grid.bounds().min, glm::ivec3(-3, -2, 0));
    EXPECT_EQ(grid.bounds().max, glm::ivec3(6, 5, 18));
    EXPECT_EQ(grid.bytes(), grid.blob().size() * 4);
}
