// Appearance inputs that are wrong get a clear error or a defined result: table files of
// another version, truncated, corrupted or with faces outside their pool; tables whose
// rows are out of order; meshes without colour, with degenerate triangles or a non-finite
// vertex.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <fstream>
#include <string>

#include "error_of.hpp"
#include "temp_dir.hpp"
#include "voxray/appearance/precompute.hpp"
#include "voxray/appearance/table_file.hpp"
#include "voxray/cpu/appearance_walk.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/embree/triangle_scene.hpp"
#include "walk_tables.hpp"

namespace voxray {
namespace {

using namespace appearance;
using test::error_of;

std::vector<unsigned char> file_bytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}

void write_bytes(const std::filesystem::path& p, const std::vector<unsigned char>& b) {
    std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

// Rewrites the checksum of a file's bytes after an edit, so that the content checks run.
void reseal(std::vector<unsigned char>& b) {
    std::vector<unsigned char> body(b.begin() + table_file_header_bytes, b.end());
    std::uint64_t sum = table_file_detail::checksum(b.data(), body);
    std::memcpy(b.data() + 32, &sum, 8);
}

voxel_model small_block() {
    voxel_model m;
    for (int z = 0; z < 3; ++z)
        for (int y = 0; y < 5; ++y)
            for (int x = 0; x < 6; ++x) m.set({x, y, z}, 1);
    return m;
}

TEST(appearance_bad_input, table_files_round_trip_every_kind) {
    test::temp_dir dir;
    appearance_table compact = test::uniform_table(small_block(), 9);
    save_table(compact, dir.path / "compact.vxap");
    appearance_table back = load_table(dir.path / "compact.vxap");
    EXPECT_EQ(back.kind, compact.kind);
    EXPECT_EQ(back.voxels, compact.voxels);
    EXPECT_EQ(back.words, compact.words);
    EXPECT_EQ(back.faces, compact.faces);
    for (record_kind k : {record_kind::averages, record_kind::six, record_kind::sggx}) {
        appearance_table t;
        t.kind = k, t.record_words = record_words(k), t.voxels = compact.voxels;
        for (std::size_t i = 0; i < t.voxels.size() * std::size_t(t.record_words); ++i)
            t.words.push_back(std::uint32_t(i * 2654435761u));
        save_table(t, dir.path / "t.vxap");
        appearance_table u = load_table(dir.path / "t.vxap");
        EXPECT_EQ(u.kind, k);
        EXPECT_EQ(u.words, t.words);
        EXPECT_EQ(u.voxels, t.voxels);
    }
}

TEST(appearance_bad_input, table_files_that_are_wrong_name_the_offset_and_the_value) {
    test::temp_dir dir;
    std::filesystem::path p = dir.path / "table.vxap";
    save_table(test::uniform_table(small_block(), 9), p);
    const std::vector<unsigned char> good = file_bytes(p);
    auto load_edited = [&](auto&& edit) {
        std::vector<unsigned char> b = good;
        edit(b);
        write_bytes(p, b);
        return error_of([&] { load_table(p); });
    };
    EXPECT_NE(load_edited([](auto& b) { b[4] = 3; }).find("offset 4: unsupported version 3"), std::string::npos);
    EXPECT_NE(load_edited([](auto& b) { b[44] = 1; }).find("offset 44: reserved word is 1"), std::string::npos);
    EXPECT_NE(load_edited([](auto& b) { b[0] = 'X'; }).find("offset 0: bad magic"), std::string::npos);
    EXPECT_NE(load_edited([](auto& b) { b.resize(b.size() - 4); }).find("offset 16: file is"), std::string::npos);
    EXPECT_NE(load_edited([](auto& b) { b.resize(20); }).find("truncated"), std::string::npos);
    EXPECT_NE(load_edited([](auto& b) { b[60] ^= 1; }).find("offset 32: checksum"), std::string::npos);
    EXPECT_NE(load_edited([](auto& b) { b[8] = 7, reseal(b); }).find("offset 8: unknown record kind 7"),
              std::string::npos);
    EXPECT_NE(load_edited([](auto& b) { b[12] = 5, reseal(b); }).find("offset 12: compact records take 3 words"),
              std::string::npos);
    // Row 2's first face far outside the pool: a walk would read past the face buffer.
    std::size_t rows = small_block().voxel_count(), records_at = table_file_header_bytes + 12 * rows;
    std::string outside = load_edited([&](auto& b) {
        std::uint32_t first = 1000000;
        std::memcpy(b.data() + records_at + 4 * 2 * VX_APP_COMPACT_WORDS, &first, 4);
        reseal(b);
    });
    EXPECT_NE(outside.find("(row 2) faces 1000000 to 1000001 outside the pool of " + std::to_string(rows) + " faces"),
              std::string::npos)
        << outside;
    // Rows 0 and 1 swapped: the ordinal index would give the walk the wrong records.
    std::string swapped = load_edited([&](auto& b) {
        std::swap_ranges(b.begin() + table_file_header_bytes, b.begin() + table_file_header_bytes + 12,
                         b.begin() + table_file_header_bytes + 12);
        reseal(b);
    });
    EXPECT_NE(swapped.find("(row 1) voxel (0, 0, 0) is not after the row before it"), std::string::npos) << swapped;
    write_bytes(p, good);
    EXPECT_NO_THROW(load_table(p));
}

TEST(appearance_bad_input, a_walker_refuses_a_table_whose_faces_leave_the_pool) {
    voxel_model block = small_block();
    appearance_table t = test::uniform_table(block, 15);
    t.faces.resize(t.faces.size() - 2);  // the last row's face is gone
    dense_grid grid(block);
    std::string e = error_of([&] {
        appearance_walker<kernels::dense_grid_kernel> w({grid.blob().begin(), grid.blob().end()}, t, 1);
    });
    EXPECT_NE(e.find("appearance walk: the table: row " + std::to_string(t.size() - 1) + ": faces"), std::string::npos)
        << e;
}

// Voxel space is world space here: one voxel a unit from the origin.
io::voxel_grid_map unit_voxels() {
    io::voxel_grid_map g;
    g.dims = {16, 16, 16};
    return g;
}

// A 4 x 4 square at z = 0.5 facing +z, two triangles, with `extra` triangles after them.
io::triangle_mesh square(std::vector<glm::dvec3> extra = {}) {
    io::triangle_mesh m;
    m.positions = {{0, 0, 0.5}, {4, 0, 0.5}, {4, 4, 0.5}, {0, 4, 0.5}};
    m.triangles = {{0, 1, 2}, {0, 2, 3}};
    for (std::size_t i = 0; i + 2 < extra.size(); i += 3) {
        auto base = std::uint32_t(m.positions.size());
        m.positions.insert(m.positions.end(), extra.begin() + i, extra.begin() + i + 3);
        m.triangles.push_back({base, base + 1, base + 2});
    }
    return m;
}

voxel_model square_voxels() {
    voxel_model v;
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) v.set({x, y, 0}, 1);
    return v;
}

TEST(appearance_bad_input, a_mesh_without_colour_is_white) {
    io::triangle_mesh m = square();
    embree::triangle_scene scene(m, unit_voxels());
    appearance_table t = precompute(scene, m, square_voxels(), {.threads = 1});
    for (std::size_t row = 0; row < t.size(); ++row) {
        std::uint32_t w0 = t.record(row)[0];
        EXPECT_EQ(VX_APP_AVG_R(w0), 255u) << row;
        EXPECT_EQ(VX_APP_AVG_G(w0), 255u) << row;
        EXPECT_EQ(VX_APP_AVG_B(w0), 255u) << row;
    }
}

TEST(appearance_bad_input, degenerate_triangles_change_nothing) {
    io::triangle_mesh plain = square();
    // A triangle with a repeated corner and one whose corners are on a line, both inside
    // the square's voxels.
    io::triangle_mesh degenerate = square({{1, 1, 0.5}, {1, 1, 0.5}, {2, 2, 0.5}, {0.5, 0.5, 0.3}, {1.5, 1.5, 0.4},
                                           {2.5, 2.5, 0.5}});
    for (record_kind k : {record_kind::averages, record_kind::compact}) {
        embree::triangle_scene a(plain, unit_voxels()), b(degenerate, unit_voxels());
        appearance_table ta = precompute(a, plain, square_voxels(), {.kind = k, .threads = 1});
        appearance_table tb = precompute(b, degenerate, square_voxels(), {.kind = k, .threads = 1});
        EXPECT_EQ(ta.words, tb.words) << record_name(k);
        EXPECT_EQ(ta.faces, tb.faces) << record_name(k);
    }
}

TEST(appearance_bad_input, a_non_finite_vertex_is_an_error_naming_it) {
    io::triangle_mesh m = square({{1, 1, 0.5}, {2, 1, 0.5}, {1, std::nan(""), 0.5}});
    std::string e = error_of([&] {
        embree::triangle_scene scene(m, unit_voxels());
        precompute(scene, m, square_voxels(), {.threads = 1});
    });
    EXPECT_NE(e.find("mesh vertex 6 has a non-finite coordinate"), std::string::npos) << e;
}

}  // namespace
}  // namespace voxray
