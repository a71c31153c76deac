// Coloured inputs (voxray::gltf, io/mesh_surface.hpp): OBJ with MTL and textures, glTF with
// node transforms, factors, textures and alpha modes; voxels take the colour of what they
// cover, cut-outs drop voxels, the palette is a median cut, thread count changes nothing;
// bad input gets an error naming the file and the problem.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include "mesh_test_util.hpp"
#include "test_data.hpp"
#include "voxray/gltf/coloured_mesh.hpp"
#include "voxray/io/colour_palette.hpp"

namespace voxray {
namespace {

void write_text(const std::filesystem::path& p, const std::string& text) { std::ofstream(p, std::ios::binary) << text; }

// An uncompressed 32-bit TGA, rows top to bottom; `texel(x, y)` gives RGBA.
template <class F>
void write_tga(const std::filesystem::path& p, int w, int h, F texel) {
    std::vector<unsigned char> b(18, 0);
    b[2] = 2;  // uncompressed true colour
    b[12] = std::uint8_t(w), b[13] = std::uint8_t(w >> 8), b[14] = std::uint8_t(h), b[15] = std::uint8_t(h >> 8);
    b[16] = 32, b[17] = 0x28;  // 8 alpha bits, top-left origin
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            rgba c = texel(x, y);
            b.insert(b.end(), {c.b, c.g, c.r, c.a});  // TGA stores BGRA
        }
    std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

// The texture of the OBJ test: quadrants red (top left), green, blue, white (bottom right);
// in the alpha variant the left half is transparent.
rgba quadrant(int x, int y, bool cut) {
    rgba c = y < 8 ? (x < 8 ? rgba{255, 0, 0, 255} : rgba{0, 255, 0, 255})
                   : (x < 8 ? rgba{0, 0, 255, 255} : rgba{255, 255, 255, 255});
    if (cut && x < 8) c.a = 0;
    return c;
}

// A unit square in z = 0 textured with `texture`, as OBJ + MTL.
std::filesystem::path write_square_obj(const std::filesystem::path& dir, const std::string& map_line) {
    write_text(dir / "square.mtl", "newmtl painted\nKd 1 1 1\n" + map_line + "\n");
    write_text(dir / "square.obj", "mtllib square.mtl\n"
                                   "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
                                   "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                   "usemtl painted\nf 1/1 2/2 3/3 4/4\n");
    return dir / "square.obj";
}

rgba colour_at(const voxel_model& m, int x, int y) { return m.palette()[m.get({x, y, 0})].colour; }

TEST(coloured_meshes, an_obj_texture_colours_the_voxels_it_covers) {
    test::temp_dir dir;
    write_tga(dir.path() / "quadrants.tga", 16, 16, [](int x, int y) { return quadrant(x, y, false); });
    voxel_model m = gltf::load_coloured_mesh_model(write_square_obj(dir.path(), "map_Kd quadrants.tga"), 16);
    EXPECT_EQ(m.voxel_count(), 16u * 16u);
    // OBJ's v points up, the texture's rows down: the top-left quadrant is at high y.
    for (int y : {2, 5})
        for (int x : {2, 5}) {
            EXPECT_EQ(colour_at(m, x, 15 - y), (rgba{255, 0, 0, 255})) << x << ", " << y;
            EXPECT_EQ(colour_at(m, 15 - x, 15 - y), (rgba{0, 255, 0, 255})) << x << ", " << y;
            EXPECT_EQ(colour_at(m, x, y), (rgba{0, 0, 255, 255})) << x << ", " << y;
            EXPECT_EQ(colour_at(m, 15 - x, y), (rgba{255, 255, 255, 255})) << x << ", " << y;
        }
}

TEST(coloured_meshes, a_coverage_texture_cuts_out_voxels) {
    test::temp_dir dir;
    write_tga(dir.path() / "cut.tga", 16, 16, [](int x, int y) { return quadrant(x, y, true); });
    voxel_model m = gltf::load_coloured_mesh_model(write_square_obj(dir.path(), "map_Kd cut.tga"), 16);
    // The left half is transparent: no voxel left of x = 7, all of them right of x = 8.
    for (int y = 0; y < 16; ++y) {
        for (int x = 0; x < 7; ++x) EXPECT_EQ(m.get({x, y, 0}), 0) << x << ", " << y;
        for (int x = 9; x < 16; ++x) EXPECT_NE(m.get({x, y, 0}), 0) << x << ", " << y;
    }
}

TEST(coloured_meshes, bad_obj_materials_are_errors_naming_the_problem) {
    test::temp_dir dir;
    auto expect_error = [](const std::filesystem::path& p, const std::string& part) {
        try {
            gltf::load_coloured_mesh(p);
            FAIL() << "no error for " << p;
        } catch (const error& e) {
            EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
        }
    };
    expect_error(write_square_obj(dir.path(), "map_Kd missing.tga"), "missing.tga");
    write_text(dir.path() / "bad.tga", "not an image");
    expect_error(write_square_obj(dir.path(), "map_Kd bad.tga"), "cannot be decoded");
    write_text(dir.path() / "square.mtl", "newmtl painted\nKd 1 nan 1\n");
    expect_error(dir.path() / "square.obj", "square.mtl:2");
    write_text(dir.path() / "square.mtl", "newmtl painted\nKd 1 1 1\n");
    write_text(dir.path() / "other.obj", "mtllib square.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl nothing\nf 1 2 3\n");
    expect_error(dir.path() / "other.obj", "other.obj:5");
    write_text(dir.path() / "nolib.obj", "mtllib absent.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    expect_error(dir.path() / "nolib.obj", "absent.mtl");
    write_text(dir.path() / "uv.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 nan\nf 1/1 2/1 3/1\n");
    expect_error(dir.path() / "uv.obj", "uv.obj:4");
    // No material at all: a defined result, the groups' palette, as before.
    write_text(dir.path() / "plain.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    EXPECT_FALSE(gltf::load_coloured_mesh(dir.path() / "plain.obj").surface.coloured());
}

// A glTF of one right triangle (legs 1 along x and y) with a node that turns it (x -> -z,
// quarter turn about y), a red factor and a MASK material; the buffer is a data URI.
std::string base64(const std::vector<unsigned char>& in) {
    static const char* digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    for (std::size_t i = 0; i < in.size(); i += 3) {
        std::uint32_t v = std::uint32_t(in[i]) << 16 | (i + 1 < in.size() ? std::uint32_t(in[i + 1]) << 8 : 0u) |
                          (i + 2 < in.size() ? std::uint32_t(in[i + 2]) : 0u);
        out += digits[(v >> 18) & 63];
        out += digits[(v >> 12) & 63];
        out += i + 1 < in.size() ? digits[(v >> 6) & 63] : '=';
        out += i + 2 < in.size() ? digits[v & 63] : '=';
    }
    return out;
}

std::string triangle_gltf(const std::string& material, const std::string& node_extra, std::size_t position_bytes = 36) {
    float xyz[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    std::vector<unsigned char> bytes(reinterpret_cast<unsigned char*>(xyz), reinterpret_cast<unsigned char*>(xyz) + 36);
    return R"({"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
  "nodes": [{"mesh": 0)" + node_extra + R"(}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
  "materials": [)" + material + R"(],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}],
  "bufferViews": [{"buffer": 0, "byteLength": )" + std::to_string(position_bytes) + R"(}],
  "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,)" + base64(bytes) + R"("}]})";
}

TEST(coloured_meshes, gltf_node_transforms_and_factors) {
    test::temp_dir dir;
    write_text(dir.path() / "turned.gltf",
               triangle_gltf(R"({"pbrMetallicRoughness": {"baseColorFactor": [1, 0, 0, 1]}})",
                             R"(, "rotation": [0, 0.7071068, 0, 0.7071068])"));
    io::triangle_mesh mesh = gltf::load_coloured_mesh(dir.path() / "turned.gltf");
    ASSERT_EQ(mesh.triangle_count(), 1u);
    // The quarter turn about y takes (1, 0, 0) to (0, 0, -1).
    glm::dvec3 turned = mesh.positions[mesh.triangles[0].y];
    EXPECT_NEAR(turned.x, 0.0, 1e-6);
    EXPECT_NEAR(turned.z, -1.0, 1e-6);
    voxel_model m = io::voxelize(mesh, {.resolution = 8});
    ASSERT_GT(m.voxel_count(), 0u);
    EXPECT_EQ(m.palette()[m.get(m.bounds().min)].colour, (rgba{255, 0, 0, 255}));
    // MASK with the factor's alpha below the cutoff: nothing is left.
    write_text(dir.path() / "masked.gltf",
               triangle_gltf(R"({"pbrMetallicRoughness": {"baseColorFactor": [1, 1, 1, 0.2]},
                                 "alphaMode": "MASK", "alphaCutoff": 0.5})",
                             ""));
    EXPECT_EQ(io::voxelize(gltf::load_coloured_mesh(dir.path() / "masked.gltf"), {.resolution = 8}).voxel_count(), 0u);
}

TEST(coloured_meshes, bad_gltf_is_an_error_naming_the_file_and_the_problem) {
    test::temp_dir dir;
    write_text(dir.path() / "short.gltf", triangle_gltf("{}", "", 48));  // the view claims more than the buffer has
    try {
        gltf::load_coloured_mesh(dir.path() / "short.gltf");
        FAIL() << "no error";
    } catch (const error& e) {
        EXPECT_NE(std::string(e.what()).find("short.gltf"), std::string::npos) << e.what();
    }
    write_text(dir.path() / "broken.gltf", "{ not json");
    EXPECT_THROW(gltf::load_coloured_mesh(dir.path() / "broken.gltf"), error);
    EXPECT_THROW(gltf::load_coloured_mesh(dir.path() / "absent.glb"), error);
}

TEST(coloured_meshes, median_cut_keeps_few_colours_exactly_and_caps_many) {
    std::vector<io::colour_count> few;
    for (std::uint32_t i = 0; i < 200; ++i) few.push_back({i * 0x010203u, i + 1});
    io::median_cut_palette p = io::median_cut(few, 255);
    ASSERT_EQ(p.entries.size(), 200u);
    for (const io::colour_count& c : few) {
        rgba e = p.entries[p.entry.at(c.rgb)];
        EXPECT_EQ(std::uint32_t(e.r) | std::uint32_t(e.g) << 8 | std::uint32_t(e.b) << 16, c.rgb);
    }
    std::vector<io::colour_count> many;
    for (std::uint32_t i = 0; i < 5000; ++i) many.push_back({(i * 2654435761u) & 0xFFFFFFu, 1});
    io::median_cut_palette q = io::median_cut(many, 255);
    EXPECT_EQ(q.entries.size(), 255u);
    EXPECT_EQ(q.entry.size(), many.size());
}

TEST(coloured_meshes, shared_gltf_scenes_take_their_materials_colours) {
    VOXRAY_REQUIRE_DATA();
    // The kitchen: 8 flat factor colours, so every voxel's colour is one of theirs.
    auto kitchen = *test::data_dir() / "mesh" / "kitchen" / "scene.gltf";
    io::triangle_mesh mesh = gltf::load_coloured_mesh(kitchen);
    std::vector<rgba> factors;
    for (const io::mesh_material& mat : mesh.surface.materials) factors.push_back(io::encode_srgb8(mat.base_colour));
    voxel_model m = io::voxelize(mesh, {.resolution = 96, .threads = 2});
    ASSERT_GT(m.voxel_count(), 10000u);
    std::uint64_t off = 0;
    m.for_each_voxel([&](glm::ivec3, std::uint8_t v) {
        rgba c = m.palette()[v].colour;
        bool near = false;
        for (rgba f : factors)
            near = near || (std::abs(c.r - f.r) <= 2 && std::abs(c.g - f.g) <= 2 && std::abs(c.b - f.b) <= 2);
        off += !near;
    });
    EXPECT_EQ(off, 0u);
    // The same voxels and colours on one thread.
    voxel_model one = io::voxelize(mesh, {.resolution = 96, .threads = 1});
    EXPECT_EQ(one.voxel_count(), m.voxel_count());
    std::uint64_t differ = 0;
    m.for_each_voxel([&](glm::ivec3 p, std::uint8_t v) {
        differ += one.palette()[one.get(p)].colour != m.palette()[v].colour;
    });
    EXPECT_EQ(differ, 0u);
}

TEST(coloured_meshes, leaf_cards_are_cut_out_by_their_textures_alpha) {
    VOXRAY_REQUIRE_DATA();
    io::triangle_mesh mesh = gltf::load_coloured_mesh(*test::data_dir() / "mesh" / "small_tree" / "scene.gltf");
    voxel_model cut = io::voxelize(mesh, {.resolution = 128});
    for (io::mesh_material& mat : mesh.surface.materials) mat.alpha = io::alpha_mode::opaque;
    voxel_model solid = io::voxelize(mesh, {.resolution = 128});
    // 80 % of the leaf texture is transparent: the cut-out tree has far fewer voxels.
    EXPECT_LT(double(cut.voxel_count()), 0.8 * double(solid.voxel_count()))
        << cut.voxel_count() << " voxels cut out, " << solid.voxel_count() << " without the alpha test";
    EXPECT_GT(cut.voxel_count(), 0u);
}

TEST(coloured_meshes, textured_gltf_gives_many_colours) {
    VOXRAY_REQUIRE_DATA();
    // The helmet's six textured materials: far more colours than materials.
    auto helmet = *test::data_dir() / "mesh" / "flight_helmet" / "FlightHelmet.gltf";
    voxel_model m = gltf::load_coloured_mesh_model(helmet, 64);
    std::set<std::uint8_t> used;
    m.for_each_voxel([&](glm::ivec3, std::uint8_t v) { used.insert(v); });
    EXPECT_GT(used.size(), 100u);
}

}  // namespace
}  // namespace voxray
