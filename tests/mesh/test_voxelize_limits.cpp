// Issue 12, item 10: an OBJ of 20,000 copies of one big triangle took over 20 s at
// resolution 512. A triangle that repeats an earlier one is now voxelized once (counted,
// not timed), and the work of the rest is estimated up front against a caller's limit.
#include <string>

#include <gtest/gtest.h>

#include "mesh_test_util.hpp"
#include "voxray/io/mesh_loader.hpp"
#include "voxray/io/voxelizer.hpp"

namespace {

using namespace voxray;
using namespace voxray::io;
using voxray::test::expect_error;
using voxray::test::model_hash;
using voxray::test::temp_dir;

// `copies` copies of one big slanted triangle, each with its own three 'v' lines, in
// groups that change every 1000 triangles (a later group cannot recolour a voxel).
std::string repeated_triangle_obj(int copies, double shift = 0.0) {
    std::string obj;
    for (int i = 0; i < copies; ++i) {
        if (i % 1000 == 0) obj += "g part" + std::to_string(i / 1000) + "\n";
        double s = shift * i;
        obj += "v " + std::to_string(s) + " 0 0\nv 1 0.3 " + std::to_string(0.2 + s) + "\nv 0.2 1 0.7\nf -3 -2 -1\n";
    }
    return obj;
}

TEST(VoxelizeLimits, RepeatedTrianglesAreVoxelizedOnce) {
    temp_dir dir;
    auto one = load_mesh(dir.write("one.obj", repeated_triangle_obj(1)));
    auto many = load_mesh(dir.write("many.obj", repeated_triangle_obj(20000)));
    ASSERT_EQ(many.triangle_count(), 20000u);
    voxelize_stats s1, s2;
    auto a = voxelize(one, {512, 2}, &s1);
    auto b = voxelize(many, {512, 2}, &s2);
    EXPECT_EQ(s2.triangles, 20000u);
    EXPECT_EQ(s2.unique_triangles, 1u);
    EXPECT_EQ(s2.rasterized, s1.rasterized);        // each (triangle, tile) once, as for one triangle
    EXPECT_EQ(s2.cells_tested, s1.cells_tested);
    EXPECT_GT(s1.cells_tested, 100000u);             // a big triangle: the work is real
    EXPECT_EQ(b.voxel_count(), a.voxel_count());
    EXPECT_EQ(model_hash(b), model_hash(a));         // the same voxels, the same colours
}

// Only exact repeats are merged: the same triangle with its vertices in another order,
// or moved by one ulp, is voxelized too.
TEST(VoxelizeLimits, OnlyExactRepeatsAreMerged) {
    triangle_mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0.3}, {0.2, 1, 0.7}, {std::nextafter(0.2, 1.0), 1, 0.7}};
    m.triangles = {{0, 1, 2}, {1, 2, 0}, {0, 1, 3}, {0, 1, 2}};
    m.group_names = {"g"};
    voxelize_stats s;
    voxelize(m, {64, 1}, &s);
    EXPECT_EQ(s.unique_triangles, 3u);
}

// The estimate bounds the real work on different shapes (so the limit means something).
TEST(VoxelizeLimits, TheEstimateCoversTheCellsTested) {
    temp_dir dir;
    triangle_mesh box;
    voxray::test::add_box(box, {0, 0, 0}, {1, 0.5, 0.8});
    for (auto* mesh : {&box}) {
        for (int res : {1, 7, 64, 300}) {
            voxelize_stats s;
            voxelize(*mesh, {res, 2}, &s);
            EXPECT_LE(s.cells_tested, s.estimated_cells) << "resolution " << res;
        }
    }
    for (int res : {1, 5, 64, 512}) {
        voxelize_stats s;
        voxelize(load_mesh(dir.write("fan.obj", repeated_triangle_obj(50, 0.01))), {res, 2}, &s);
        EXPECT_EQ(s.unique_triangles, 50u);
        EXPECT_LE(s.cells_tested, s.estimated_cells) << "resolution " << res;
    }
}

// Many distinct big triangles: refused before any is rasterized, with the numbers and
// (through the loader) the file.
TEST(VoxelizeLimits, TheWorkLimitIsCheckedUpFront) {
    temp_dir dir;
    auto path = dir.write("distinct.obj", repeated_triangle_obj(2000, 1e-4));
    auto mesh = load_mesh(path);
    voxelize_stats s;
    expect_error([&] { voxelize(mesh, {512, 2, 1'000'000}, &s); }, "voxelizing 2000 distinct triangles (of 2000)",
                 "at resolution 512", "above the limit of 1000000");
    EXPECT_EQ(s.rasterized, 0u);  // stats are only written on success: nothing ran
    expect_error([&] { load_mesh_model(path, 512, {.threads = 2, .max_cell_tests = 1'000'000}); },
                 path.string() + ": voxelizing 2000", "above the limit of 1000000");
    EXPECT_EQ(voxelize(mesh, {16, 2, 10'000'000}).up_axis, 2);  // a lower resolution fits
}

}  // namespace
