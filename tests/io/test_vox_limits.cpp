// Issue 12, item 10: a small .vox that instances one model a million times must be
// refused before it is expanded, with the file, the count and the limit in the message,
// and the limits are the caller's to set.
#include <string>

#include <gtest/gtest.h>

#include "vox_bytes.hpp"
#include "vox_errors.hpp"
#include "voxray/io/vox_reader.hpp"

namespace {

using namespace voxray;
using namespace voxray::io;
using namespace voxray::test::vox_bytes;

// A 16x16x1 model (256 voxels) placed on an outer x inner grid of instances, 16 apart:
// root -> group of `outer` transforms -> one shared group of `inner` transforms -> shape.
// 1024 x 1024 is the issue's file: 128 KB, 2^20 instances, 2^28 voxels.
bytes instanced_grid(int outer, int inner, int model_edge = 16, int spacing = 16) {
    std::vector<std::array<std::uint8_t, 4>> voxels;
    for (int y = 0; y < model_edge; ++y)
        for (int x = 0; x < model_edge; ++x) voxels.push_back({std::uint8_t(x), std::uint8_t(y), 0, 1});
    std::vector<bytes> chunks{size_chunk(model_edge, model_edge, 1), xyzi_chunk(voxels)};
    const int outer_group = 1, inner_group = 2 + outer, shape = inner_group + 1 + inner;
    std::vector<int> outer_ids, inner_ids;
    for (int i = 0; i < outer; ++i) outer_ids.push_back(2 + i);
    for (int i = 0; i < inner; ++i) inner_ids.push_back(inner_group + 1 + i);
    chunks.push_back(ntrn(0, outer_group, {}));
    chunks.push_back(ngrp(outer_group, outer_ids));
    for (int i = 0; i < outer; ++i)
        chunks.push_back(ntrn(outer_ids[i], inner_group, {{"_t", std::to_string(i * spacing) + " 0 0"}}));
    chunks.push_back(ngrp(inner_group, inner_ids));
    for (int i = 0; i < inner; ++i)
        chunks.push_back(ntrn(inner_ids[i], shape, {{"_t", "0 " + std::to_string(i * spacing) + " 0"}}));
    chunks.push_back(nshp(shape, {{0, {}}}));
    return vox(chunks);
}

std::string grid_error_of(const bytes& b, const vox_options& options = {}) {
    return test::vox_error_of(b, options, "grid.vox");
}

TEST(VoxLimits, TheIssuesFileIsRefusedByDefault) {
    bytes file = instanced_grid(1024, 1024);
    EXPECT_LT(file.size(), 140000u);  // a small input...
    auto msg = grid_error_of(file);        // ...that would place 2^28 voxels
    EXPECT_NE(msg.find("grid.vox: the scene places 268435456 voxels (1048576 model instances)"), std::string::npos)
        << msg;
    EXPECT_NE(msg.find("above the limit of 134217728 placed voxels"), std::string::npos) << msg;
}

// The total is counted before anything is placed: the message names all of it, not the
// point where placing crossed the limit.
TEST(VoxLimits, TheVoxelLimitIsCheckedUpFrontWithTheTotal) {
    auto msg = grid_error_of(instanced_grid(64, 64), {.max_placed_voxels = 100000});
    EXPECT_NE(msg.find("places 1048576 voxels (4096 model instances), above the limit of 100000"), std::string::npos)
        << msg;
}

// Single voxels far apart each cost a whole 16^3 chunk: memory, not voxels, is the limit.
TEST(VoxLimits, TheMemoryBoundIsCheckedUpFront) {
    bytes file = instanced_grid(200, 200, 1, 32);
    auto msg = grid_error_of(file, {.max_model_bytes = 64 << 20});
    EXPECT_NE(msg.find("grid.vox: the scene's 40000 model instances may need up to"), std::string::npos) << msg;
    EXPECT_NE(msg.find("above the limit of 67108864 bytes"), std::string::npos) << msg;
    // With the default limit it loads, and the bound it checked covers what it built.
    auto scene = read_vox_scene(file, "grid.vox");
    EXPECT_EQ(scene.model.voxel_count(), 40000u);
    EXPECT_GE(scene.stats.model_bytes_bound, 40000u * sizeof(voxel_model::chunk));
}

TEST(VoxLimits, TheCallerSetsTheLimits) {
    bytes file = instanced_grid(16, 16);
    EXPECT_NE(grid_error_of(file, {.max_placed_voxels = 65535}).find("above the limit of 65535"), std::string::npos);
    auto scene = read_vox_scene(file, "grid.vox", {.max_placed_voxels = 65536});
    EXPECT_EQ(scene.stats.instances, 256u);
    EXPECT_EQ(scene.stats.placed_voxels, 65536u);
    EXPECT_EQ(scene.model.voxel_count(), 65536u);
    EXPECT_EQ(scene.model.bounds().max, glm::ivec3(256, 256, 1) - glm::ivec3(8, 8, 0));
}

}  // namespace
