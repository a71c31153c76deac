// The triangle/box test against independent checks, and the voxelizer against
// brute force and hand-counted shells.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_set>
#include <vector>

#include <gtest/gtest.h>

#include "mesh_test_util.hpp"
#include "voxray/io/triangle_box.hpp"
#include "voxray/io/voxelizer.hpp"

namespace {

using glm::dvec3;
using voxray::io::triangle_mesh;

struct rng {
    std::uint64_t s;
    std::uint64_t next() {
        std::uint64_t z = (s += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    double uniform(double lo, double hi) { return lo + (hi - lo) * double(next() >> 11) * 0x1.0p-53; }
    dvec3 point(double lo, double hi) { return {uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)}; }
};

// Independent overlap check: clip the triangle by the box's six half-spaces
// (Sutherland-Hodgman); anything left means they meet.
bool clipped_nonempty(std::vector<dvec3> poly, dvec3 lo, dvec3 hi) {
    for (int axis = 0; axis < 3 && !poly.empty(); ++axis)
        for (int side = 0; side < 2 && !poly.empty(); ++side) {
            auto inside = [&](const dvec3& p) { return side ? p[axis] <= hi[axis] : p[axis] >= lo[axis]; };
            double plane = side ? hi[axis] : lo[axis];
            std::vector<dvec3> out;
            for (std::size_t i = 0; i < poly.size(); ++i) {
                const dvec3 &a = poly[i], &b = poly[(i + 1) % poly.size()];
                if (inside(a)) out.push_back(a);
                if (inside(a) != inside(b)) out.push_back(a + (b - a) * ((plane - a[axis]) / (b[axis] - a[axis])));
            }
            poly = std::move(out);
        }
    return !poly.empty();
}

double distance_to_box(dvec3 p, dvec3 lo, dvec3 hi) {
    dvec3 d = glm::max(glm::max(lo - p, p - hi), dvec3(0.0));
    return std::sqrt(glm::dot(d, d));
}

// A random triangle near the unit cell: generic, sliver, axis-snapped (touching
// cases where all arithmetic is exact), or degenerate.
std::vector<dvec3> random_triangle(rng& r, int kind) {
    dvec3 a = r.point(-1, 2), b = r.point(-1, 2), c = r.point(-1, 2);
    if (kind == 1) c = a + (b - a) * r.uniform(0, 1) + r.point(-1e-3, 1e-3);
    if (kind == 2) a = glm::round(a), b = glm::round(b), c = glm::round(c);
    if (kind == 3) c = a + (b - a) * 0.5;
    return {a, b, c};
}

TEST(TriangleBox, AgreesWithClippingAndSampling) {
    rng r{12345};
    const dvec3 lo(0.0), hi(1.0);
    int overlaps = 0, total = 0;
    for (int i = 0; i < 20000; ++i) {
        auto t = random_triangle(r, i % 4);
        bool sat = voxray::io::triangle_box_overlap(dvec3(0.5), dvec3(0.5), t[0], t[1], t[2]);
        voxray::io::triangle_cell_test cell(t[0], t[1], t[2]);
        ASSERT_EQ(sat, cell.overlaps(dvec3(0.0))) << "case " << i;
        // Exact up to rounding: a reported overlap survives a box grown by 1e-9,
        // a reported miss leaves nothing in a box shrunk by 1e-9.
        if (sat) {
            EXPECT_TRUE(clipped_nonempty(t, lo - 1e-9, hi + 1e-9)) << "false overlap, case " << i;
        } else {
            EXPECT_FALSE(clipped_nonempty(t, lo + 1e-9, hi - 1e-9)) << "missed overlap, case " << i;
        }

        // Sampling: every sample inside the box demands an overlap; an overlap
        // demands a sample within one sub-triangle diameter of the box.
        constexpr int steps = 24;
        double edge = std::max({glm::length(t[1] - t[0]), glm::length(t[2] - t[1]), glm::length(t[0] - t[2])});
        double nearest = 1e30;
        for (int a = 0; a <= steps; ++a)
            for (int b = 0; a + b <= steps; ++b) {
                dvec3 p = t[0] + (t[1] - t[0]) * (double(a) / steps) + (t[2] - t[0]) * (double(b) / steps);
                double d = distance_to_box(p, lo, hi);
                nearest = std::min(nearest, d);
                if (d == 0.0) {
                    ASSERT_TRUE(sat) << "sample inside the box but no overlap, case " << i;
                }
            }
        if (sat) {
            EXPECT_LE(nearest, edge / steps + 1e-12) << "case " << i;
        }
        overlaps += sat;
        ++total;
    }
    // Both outcomes must be well represented for the test to mean anything.
    EXPECT_GT(overlaps, total / 10);
    EXPECT_LT(overlaps, total * 9 / 10);
}

// Every cell that brute force finds, and only those, with the first triangle's colour.
void expect_matches_brute_force(const triangle_mesh& mesh, int resolution, unsigned threads) {
    auto model = voxray::io::voxelize(mesh, {resolution, threads});
    auto grid = voxray::io::make_grid_map(mesh.bounds(), resolution);
    std::unordered_set<std::uint64_t> seen;
    auto key = [](glm::ivec3 p) { return std::uint64_t(p.x) | (std::uint64_t(p.y) << 21) | (std::uint64_t(p.z) << 42); };
    std::uint64_t expected = 0;
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        dvec3 v[3];
        for (int k = 0; k < 3; ++k) v[k] = grid.to_voxel(mesh.positions[mesh.triangles[t][k]]);
        glm::ivec3 c0 = glm::max(glm::ivec3(glm::floor(glm::min(v[0], glm::min(v[1], v[2])))) - 1, glm::ivec3(0));
        glm::ivec3 c1 = glm::min(glm::ivec3(glm::floor(glm::max(v[0], glm::max(v[1], v[2])))), grid.dims - 1);
        glm::ivec3 p;
        for (p.z = c0.z; p.z <= c1.z; ++p.z)
            for (p.y = c0.y; p.y <= c1.y; ++p.y)
                for (p.x = c0.x; p.x <= c1.x; ++p.x) {
                    if (!voxray::io::triangle_box_overlap(dvec3(p) + 0.5, dvec3(0.5), v[0], v[1], v[2])) continue;
                    if (!seen.insert(key(p)).second) continue;
                    ++expected;
                    ASSERT_EQ(model.get(p), voxray::io::group_palette_index(mesh.groups[t]))
                        << "cell " << p.x << "," << p.y << "," << p.z << " triangle " << t;
                }
    }
    EXPECT_EQ(model.voxel_count(), expected);
    // Cells holding a vertex are always set.
    for (auto& pos : mesh.positions) {
        glm::ivec3 c = glm::clamp(glm::ivec3(glm::floor(grid.to_voxel(pos))), glm::ivec3(0), grid.dims - 1);
        EXPECT_NE(model.get(c), 0);
    }
}

triangle_mesh random_mesh(std::uint64_t seed, int count, double size) {
    rng r{seed};
    triangle_mesh m;
    m.group_names = {"a", "b", "c"};
    for (int i = 0; i < count; ++i) {
        dvec3 centre = r.point(0, 1);
        for (int k = 0; k < 3; ++k) m.positions.push_back(glm::clamp(centre + r.point(-size, size), 0.0, 1.0));
        if (i % 7 == 3) m.positions.back() = m.positions[m.positions.size() - 2];  // degenerate: a segment
        if (i % 11 == 5) m.positions[m.positions.size() - 2] = m.positions.back() = m.positions[m.positions.size() - 3];
        auto b = std::uint32_t(m.positions.size() - 3);
        m.triangles.push_back({b, b + 1, b + 2});
        m.groups.push_back(std::uint32_t(r.next() % 3));
    }
    return m;
}

TEST(Voxelizer, MatchesBruteForceSmall) {
    for (std::uint64_t seed = 1; seed <= 6; ++seed)
        expect_matches_brute_force(random_mesh(seed, 40, 0.3), 7 + int(seed) * 5, 2);
}

TEST(Voxelizer, MatchesBruteForceAcrossTiles) {
    // 300 voxels span three 128-voxel tiles per axis; triangles cross tile borders.
    expect_matches_brute_force(random_mesh(77, 12, 0.25), 300, 3);
}

TEST(Voxelizer, SameResultForAnyThreadCount) {
    auto mesh = random_mesh(5, 400, 0.2);
    auto one = voxray::io::voxelize(mesh, {200, 1});
    auto four = voxray::io::voxelize(mesh, {200, 4});
    EXPECT_EQ(one.voxel_count(), four.voxel_count());
    EXPECT_EQ(voxray::test::model_hash(one), voxray::test::model_hash(four));
}

TEST(Voxelizer, CubeShellCountsExactly) {
    triangle_mesh m;
    voxray::test::add_box(m, dvec3(0.0), dvec3(1.0));
    for (int n : {1, 2, 3, 10, 64, 129}) {
        auto model = voxray::io::voxelize(m, {n, 2});
        // Faces lie on the grid's outer planes, one voxel layer each.
        std::uint64_t inner = n > 2 ? std::uint64_t(n - 2) * (n - 2) * (n - 2) : 0;
        EXPECT_EQ(model.voxel_count(), std::uint64_t(n) * n * n - inner) << "n=" << n;
        EXPECT_EQ(model.bounds().min, glm::ivec3(0));
        EXPECT_EQ(model.bounds().max, glm::ivec3(n));
    }
    // An inner cube at [3.5, 6.5] voxels: faces mid-cell, so a 4^3 - 2^3 shell.
    voxray::test::add_box(m, dvec3(0.35), dvec3(0.65), 1);
    auto model = voxray::io::voxelize(m, {10, 1});
    EXPECT_EQ(model.voxel_count(), 488u + 56u);
    EXPECT_EQ(model.get({3, 3, 3}), voxray::io::group_palette_index(1));
    EXPECT_EQ(model.get({4, 4, 4}), 0);
    EXPECT_EQ(model.get({0, 5, 5}), voxray::io::group_palette_index(0));
}

TEST(Voxelizer, FlatMeshGetsOneLayer) {
    // A square in the plane y = 0: the y extent is zero, so one layer, dims.y == 1.
    triangle_mesh m;
    m.positions = {{0, 0, 0}, {2, 0, 0}, {2, 0, 1}, {0, 0, 1}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    m.groups = {0, 0};
    m.group_names = {"floor"};
    auto model = voxray::io::voxelize(m, {16, 1});
    EXPECT_EQ(model.voxel_count(), 16u * 8u);
    EXPECT_EQ(model.bounds().extent(), glm::ivec3(16, 1, 8));
    auto colour = model.palette()[1].colour;
    EXPECT_TRUE(colour.r || colour.g || colour.b);
}

TEST(Voxelizer, RejectsBadResolutionAndEmptyMeshes) {
    triangle_mesh m;
    voxray::test::add_box(m, dvec3(0.0), dvec3(1.0));
    using voxray::test::expect_error;
    expect_error([&] { voxray::io::voxelize(m, {0, 1}); }, "resolution 0", "1..4096");
    expect_error([&] { voxray::io::voxelize(m, {4097, 1}); }, "resolution 4097", "1..4096");
    expect_error([&] { voxray::io::voxelize(m, {-3, 1}); }, "resolution -3", "1..4096");
    expect_error([&] { voxray::io::voxelize(triangle_mesh{}, {16, 1}); }, "no triangles");
    triangle_mesh point;
    point.positions = {{1, 1, 1}};
    point.triangles = {{0, 0, 0}};
    point.groups = {0};
    point.group_names = {"p"};
    expect_error([&] { voxray::io::voxelize(point, {16, 1}); }, "zero");
    // Hand-built meshes are checked before use.
    auto bad_index = m;
    bad_index.triangles[5].y = 99;
    expect_error([&] { voxray::io::voxelize(bad_index, {16, 1}); }, "triangle 5", "vertex 99", "8 vertices");
    auto bad_groups = m;
    bad_groups.groups.pop_back();
    expect_error([&] { voxray::io::voxelize(bad_groups, {16, 1}); }, "11 group ids", "12 triangles");
    auto nan = m;
    nan.positions[3].z = std::nan("");
    expect_error([&] { voxray::io::voxelize(nan, {16, 1}); }, "vertex 3", "non-finite");
    auto no_groups = m;
    no_groups.groups.clear();
    EXPECT_EQ(voxray::io::voxelize(no_groups, {4, 1}).voxel_count(), 56u);
}

TEST(GroupPalette, StableAndWrapping) {
    EXPECT_EQ(voxray::io::group_palette_index(0), 1);
    EXPECT_EQ(voxray::io::group_palette_index(254), 255);
    EXPECT_EQ(voxray::io::group_palette_index(255), 1);
    auto a = voxray::io::group_colour("walls"), b = voxray::io::group_colour("walls");
    EXPECT_EQ(a.r, b.r);
    EXPECT_EQ(a.g, b.g);
    EXPECT_EQ(a.b, b.b);
    auto c = voxray::io::group_colour("floors");
    EXPECT_TRUE(a.r != c.r || a.g != c.g || a.b != c.b);
}

}  // namespace
