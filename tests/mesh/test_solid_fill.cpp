// Solid fill by ray parity (Embree) on closed meshes with known volumes.
#include <array>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mesh_test_util.hpp"
#include "voxray/embree/solid_fill.hpp"
#include "voxray/io/voxelizer.hpp"

namespace {

using glm::dvec3;
using voxray::io::triangle_mesh;

// Unit sphere: an octahedron with each triangle split 4^levels times, vertices
// pushed out to radius 1. Shared edges get bit-identical vertices, so the mesh
// is watertight for Embree's robust mode.
triangle_mesh make_sphere(int levels) {
    std::vector<std::array<dvec3, 3>> tris;
    const dvec3 px(1, 0, 0), nx(-1, 0, 0), py(0, 1, 0), ny(0, -1, 0), pz(0, 0, 1), nz(0, 0, -1);
    tris = {{px, py, pz}, {py, nx, pz}, {nx, ny, pz}, {ny, px, pz}, {py, px, nz}, {nx, py, nz}, {ny, nx, nz}, {px, ny, nz}};
    for (int l = 0; l < levels; ++l) {
        std::vector<std::array<dvec3, 3>> next;
        for (auto& t : tris) {
            auto mid = [](dvec3 a, dvec3 b) { return glm::normalize(a + b); };
            dvec3 ab = mid(t[0], t[1]), bc = mid(t[1], t[2]), ca = mid(t[2], t[0]);
            next.push_back({t[0], ab, ca});
            next.push_back({ab, t[1], bc});
            next.push_back({ca, bc, t[2]});
            next.push_back({ab, bc, ca});
        }
        tris = std::move(next);
    }
    triangle_mesh m;
    m.group_names = {"sphere"};
    for (auto& t : tris) {
        auto b = std::uint32_t(m.positions.size());
        for (auto& p : t) m.positions.push_back(p);
        m.triangles.push_back({b, b + 1, b + 2});
        m.groups.push_back(0);
    }
    return m;
}

TEST(SolidFill, CubeBecomesFullyFilledAlongEveryAxis) {
    triangle_mesh m;
    voxray::test::add_box(m, dvec3(0.0), dvec3(1.0));
    constexpr int n = 20;
    for (int axis = 0; axis < 3; ++axis) {
        auto model = voxray::io::voxelize(m, {n, 1});
        ASSERT_EQ(model.voxel_count(), std::uint64_t(n * n * n - 18 * 18 * 18));
        auto added = voxray::embree::fill_interior(model, m, n, {axis, 7, 2});
        EXPECT_EQ(added, std::uint64_t(18 * 18 * 18)) << "axis " << axis;
        EXPECT_EQ(model.voxel_count(), std::uint64_t(n * n * n)) << "axis " << axis;
        EXPECT_EQ(model.get({10, 10, 10}), 7);
        EXPECT_EQ(model.get({0, 10, 10}), voxray::io::group_palette_index(0));  // surface kept
    }
}

TEST(SolidFill, SphereVolumeWithinTheShell) {
    auto mesh = make_sphere(5);
    constexpr int n = 48;
    auto surface = voxray::io::voxelize(mesh, {n, 2});
    auto model = voxray::io::voxelize(mesh, {n, 2});
    voxray::embree::fill_interior(model, mesh, n);
    auto grid = voxray::io::make_grid_map(mesh.bounds(), n);

    double r_in = 1.0;  // inscribed radius of the polyhedron
    for (auto& t : mesh.triangles) {
        dvec3 a = mesh.positions[t.x], b = mesh.positions[t.y], c = mesh.positions[t.z];
        r_in = std::min(r_in, std::abs(glm::dot(glm::normalize(glm::cross(b - a, c - a)), a)));
    }
    ASSERT_GT(r_in, 0.99);
    // Every voxel centre well inside is filled; nothing outside but the surface is.
    std::uint64_t inside = 0;
    glm::ivec3 p;
    for (p.z = 0; p.z < grid.dims.z; ++p.z)
        for (p.y = 0; p.y < grid.dims.y; ++p.y)
            for (p.x = 0; p.x < grid.dims.x; ++p.x) {
                double d = glm::length(grid.origin + (dvec3(p) + 0.5) / grid.scale);
                if (d < r_in - 1e-3) {
                    ++inside;
                    ASSERT_NE(model.get(p), 0) << p.x << "," << p.y << "," << p.z;
                }
                if (d > 1.0 + 1e-3 && !surface.get(p)) {
                    ASSERT_EQ(model.get(p), 0) << p.x << "," << p.y << "," << p.z;
                }
            }
    double expected = 4.0 / 3.0 * 3.14159265358979 * std::pow(n / 2.0, 3);
    EXPECT_NEAR(double(inside), expected, 0.02 * expected);
    // Filled voxels are the surface plus centres inside the polyhedron, which lie
    // within radius 1; those between r_in - 1e-3 and 1 are few.
    EXPECT_LE(model.voxel_count(), inside + surface.voxel_count());
    EXPECT_GE(model.voxel_count(), inside);
    // Interior voxels take the surface colour by default.
    EXPECT_EQ(model.get({n / 2, n / 2, n / 2}), voxray::io::group_palette_index(0));
}

TEST(SolidFill, OpenMeshAndBadAxis) {
    triangle_mesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 1}};
    m.triangles = {{0, 1, 2}};
    m.groups = {0};
    m.group_names = {"t"};
    auto model = voxray::io::voxelize(m, {16, 1});
    auto before = model.voxel_count();
    EXPECT_EQ(voxray::embree::fill_interior(model, m, 16), 0u);  // one crossing per column: nothing
    EXPECT_EQ(model.voxel_count(), before);
    voxray::test::expect_error([&] { voxray::embree::fill_interior(model, m, 16, {3}); }, "axis 3");
}

}  // namespace
