// OBJ and PLY readers (good and malformed files) and the three shared meshes.
#include <bit>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

#include <gtest/gtest.h>

#include "mesh_test_util.hpp"
#include "test_data.hpp"
#include "voxray/io/mesh_loader.hpp"

namespace {

using voxray::test::expect_error;
using voxray::test::temp_dir;

TEST(ObjReader, NegativeIndicesQuadsAndGroups) {
    // Mixed index forms, a quad (two triangles), relative indices, CRLF, 'o' and 'g'.
    const char* text =
        "# cube corner\r\n"
        "v 0 0 0\r\n"
        "v 1 0 0 1.0\r\n"
        "v 1 1 0\r\n"
        "v 0 1 0\r\n"
        "vt 0 0\n"
        "o first\n"
        "f 1/1 2/1/1 3//1 4\n"
        "g second group\n"
        "v 0 0 1\n"
        "f -5 -4 -1\n"
        "usemtl stone\n"
        "f -2 -3 -1\n"
        "g first\n"
        "f 1 3 5\n";
    auto m = voxray::io::parse_obj(text, "mem.obj");
    ASSERT_EQ(m.positions.size(), 5u);
    ASSERT_EQ(m.triangles.size(), 5u);
    EXPECT_EQ(m.triangles[0], glm::u32vec3(0, 1, 2));
    EXPECT_EQ(m.triangles[1], glm::u32vec3(0, 2, 3));
    EXPECT_EQ(m.triangles[2], glm::u32vec3(0, 1, 4));
    EXPECT_EQ(m.triangles[3], glm::u32vec3(3, 2, 4));
    ASSERT_EQ(m.group_names.size(), 2u);
    EXPECT_EQ(m.group_names[1], "second group");
    EXPECT_EQ(m.groups, (std::vector<std::uint32_t>{0, 0, 1, 1, 0}));
    EXPECT_EQ(m.positions[1], glm::dvec3(1, 0, 0));
}

TEST(ObjReader, ForwardReferencesAreCheckedAtTheEnd) {
    auto m = voxray::io::parse_obj("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "fwd.obj");
    EXPECT_EQ(m.triangles.size(), 1u);
    expect_error([] { voxray::io::parse_obj("f 1 2 4\nv 0 0 0\nv 1 0 0\nv 0 1 0\n", "fwd.obj"); }, "fwd.obj:1",
                 "index 4", "out of range");
}

TEST(ObjReader, MalformedFilesThrowWithLineAndValue) {
    auto bad = [](const char* text, auto... parts) {
        expect_error([&] { voxray::io::parse_obj(text, "bad.obj"); }, parts...);
    };
    const char* v3 = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
    bad((std::string(v3) + "f 1 2 0\n").c_str(), "bad.obj:4", "index 0");
    bad((std::string(v3) + "f 1 2 -4\n").c_str(), "bad.obj:4", "index -4", "out of range");
    bad((std::string(v3) + "f 1 2\n").c_str(), "bad.obj:4", "2 vertices");
    bad((std::string(v3) + "f 1 2 x3\n").c_str(), "bad.obj:4", "'x3'");
    bad("v 0 0 0\nv 1 nan 0\nv 0 1 0\nf 1 2 3\n", "bad.obj:2", "non-finite", "'nan'");
    bad("v 0 0 0\nv 1 inf 0\n", "bad.obj:2", "non-finite");
    bad("v 0 0\n", "bad.obj:1", "2 coordinates");
    bad("v 0 0 1e999\n", "bad.obj:1", "'1e999'");
    bad(v3, "bad.obj", "no triangles");
    bad("", "bad.obj", "no triangles");
}

// The same two-triangle quad plus a triangle, in every PLY encoding.
struct ply_case {
    std::string header_format;
    bool binary, big;
};

template <class T>
void put(std::string& out, T value, bool big) {
    char b[sizeof(T)];
    std::memcpy(b, &value, sizeof(T));
    if (big != (std::endian::native == std::endian::big)) std::reverse(b, b + sizeof(T));
    out.append(b, sizeof(T));
}

std::string make_ply(bool binary, bool big) {
    std::string s = "ply\nformat ";
    s += !binary ? "ascii" : big ? "binary_big_endian" : "binary_little_endian";
    s += " 1.0\ncomment test\nelement vertex 5\nproperty double x\nproperty float y\nproperty float z\n"
         "property uchar red\nelement face 2\nproperty uchar flags\nproperty list uchar uint vertex_indices\n"
         "element edge 1\nproperty list ushort int vertex_index\nend_header\n";
    const double pos[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5, 0.5, 2}};
    if (!binary) {
        for (auto& p : pos) s += std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + " 7\n";
        s += "1 4 0 1 2 3\n2 3 0 1 4\n2 0 1\n";
        return s;
    }
    for (auto& p : pos) {
        put(s, p[0], big);
        put(s, float(p[1]), big);
        put(s, float(p[2]), big);
        put(s, std::uint8_t(7), big);
    }
    put(s, std::uint8_t(1), big);
    put(s, std::uint8_t(4), big);
    for (std::uint32_t i : {0u, 1u, 2u, 3u}) put(s, i, big);
    put(s, std::uint8_t(2), big);
    put(s, std::uint8_t(3), big);
    for (std::uint32_t i : {0u, 1u, 4u}) put(s, i, big);
    put(s, std::uint16_t(2), big);
    put(s, std::int32_t(0), big);
    put(s, std::int32_t(1), big);
    return s;
}

TEST(PlyReader, AsciiAndBinaryAgree) {
    temp_dir dir;
    for (int mode = 0; mode < 3; ++mode) {
        auto path = dir.write("quad" + std::to_string(mode) + ".ply", make_ply(mode > 0, mode == 2));
        auto m = voxray::io::read_ply(path);
        ASSERT_EQ(m.positions.size(), 5u) << mode;
        ASSERT_EQ(m.triangles.size(), 3u) << mode;
        EXPECT_EQ(m.triangles[0], glm::u32vec3(0, 1, 2));
        EXPECT_EQ(m.triangles[1], glm::u32vec3(0, 2, 3));
        EXPECT_EQ(m.triangles[2], glm::u32vec3(0, 1, 4));
        EXPECT_EQ(m.positions[4], glm::dvec3(0.5, 0.5, 2));
        ASSERT_EQ(m.group_names.size(), 1u);
        EXPECT_EQ(m.group_names[0], "quad" + std::to_string(mode));
        auto model = voxray::io::load_mesh_model(path, 8, {1});
        EXPECT_EQ(model.up_axis, 1);
        EXPECT_EQ(model.bounds().extent().z, 8);
    }
}

TEST(PlyReader, MalformedFilesThrow) {
    temp_dir dir;
    auto bad = [&](const std::string& bytes, auto... parts) {
        auto path = dir.write("bad.ply", bytes);
        expect_error([&] { voxray::io::read_ply(path); }, parts...);
    };
    std::string le = make_ply(true, false), ascii = make_ply(false, false);
    auto header_end = le.find("end_header\n") + 11;

    // Truncated binary data: cut inside the face list (byte offset named).
    bad(le.substr(0, le.size() - 20), "bad.ply", "truncated", "byte offset");
    bad(le.substr(0, header_end + 10), "bad.ply", "truncated", "byte offset");
    // An index past the vertex count, binary and ASCII.
    std::string big_index = le;
    std::uint32_t nine = 9;
    std::memcpy(big_index.data() + header_end + 5 * 17 + 2, &nine, 4);
    bad(big_index, "bad.ply: byte offset " + std::to_string(header_end + 5 * 17 + 2), "index 9", "out of range");
    std::string ascii_bad = ascii;
    ascii_bad.replace(ascii_bad.find("1 4 0 1 2 3"), 11, "1 4 0 1 2 5");
    bad(ascii_bad, "bad.ply:20", "index 5", "out of range");
    // Non-finite coordinates.
    std::string nan_ascii = ascii;
    nan_ascii.replace(nan_ascii.find("1.000000 1.000000"), 8, "nan");
    bad(nan_ascii, "bad.ply:17", "non-finite");
    std::string inf_bin = le;
    float inf = std::numeric_limits<float>::infinity();
    std::memcpy(inf_bin.data() + header_end + 8, &inf, 4);
    bad(inf_bin, "bad.ply: byte offset " + std::to_string(header_end + 8), "non-finite");
    // Unsupported types, header problems, no faces.
    std::string odd = ascii;
    odd.replace(odd.find("property float y"), 16, "property float128 y");
    bad(odd, "bad.ply:6", "unsupported", "'float128'");
    std::string float_index = ascii;
    float_index.replace(float_index.find("uchar uint vertex_indices"), 25, "uchar float vertex_indices");
    bad(float_index, "bad.ply:11", "float");
    bad("ply\nformat ascii 1.0\n" + std::string(70000, 'c') + "\nend_header\n", "bad.ply", "header too long");
    bad("ply\nformat ascii 1.0\n" + std::string(100, 'c') + "\n", "bad.ply", "header too long");
    bad("plx\nformat ascii 1.0\nend_header\n", "bad.ply", "not a PLY");
    bad("ply\nformat binary_middle_endian 1.0\nend_header\n", "bad.ply:2", "'binary_middle_endian'");
    bad("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
        "element face 0\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n",
        "bad.ply", "no triangles");
    bad("ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nend_header\n",
        "bad.ply", "no triangles");
    bad("ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n",
        "bad.ply", "truncated", "4000000000");
    bad(ascii.substr(0, ascii.rfind("2 0 1")), "bad.ply:22", "end of file");
    // Each coordinate exactly once: 'x y y' used to load with z silently 0.
    std::string twice = ascii;
    twice.replace(twice.find("property float z"), 16, "property float y");
    bad(twice, "bad.ply:7", "coordinate y", "declared twice");
}

TEST(MeshLoader, RejectsUnknownFilesAndResolutions) {
    temp_dir dir;
    auto path = dir.write("x.stl", "solid x\n");
    expect_error([&] { voxray::io::load_mesh_model(path, 16); }, "x.stl", "unknown extension");
    expect_error([&] { voxray::io::load_mesh_model(dir.path() / "missing.obj", 16); }, "missing.obj", "cannot");
    auto obj = dir.write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect_error([&] { voxray::io::load_mesh_model(obj, 5000); }, "resolution 5000", "1..4096");
    // 4 x 4 x 1 cells: 10 below the hypotenuse x + y = 4, 3 touching it at a corner.
    EXPECT_EQ(voxray::io::load_mesh_model(obj, 4).voxel_count(), 13u);
}

TEST(SharedMeshes, VoxelizeAt256) {
    VOXRAY_REQUIRE_DATA();
    struct expect {
        const char* file;
        std::size_t groups;
    };
    for (auto e : {expect{"stanford_bunny.ply", 1}, expect{"dabrovic_sponza.obj", 35}, expect{"sibenik.obj", 1}}) {
        auto path = *voxray::test::data_dir() / "mesh" / e.file;
        auto mesh = voxray::io::load_mesh(path);
        EXPECT_GT(mesh.triangle_count(), 60000u) << e.file;
        EXPECT_EQ(mesh.group_names.size(), e.groups) << e.file;
        auto model = voxray::io::load_mesh_model(path, 256);
        auto b = model.bounds();
        auto ext = b.extent();
        EXPECT_EQ(b.min, glm::ivec3(0)) << e.file;
        EXPECT_EQ(std::max({ext.x, ext.y, ext.z}), 256) << e.file;  // exactly, by construction
        // A surface, not a solid and not a speck: between 1% and 25% of the bounds.
        EXPECT_GT(model.voxel_count(), b.volume() / 100) << e.file;
        EXPECT_LT(model.voxel_count(), b.volume() / 4) << e.file;
        EXPECT_EQ(model.up_axis, 1);
        EXPECT_EQ(model.palette().used_entries(), int(e.groups)) << e.file;
    }
}

}  // namespace
