// What a brickmap file carries besides the blob, and content a valid checksum cannot
// vouch for: the palette (colours and materials) through build, save and load; version 1
// files (no palette) still load; a bad palette record, a world extent shrunk under its
// voxels and a non-zero reserved header word are errors naming the offset.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

#include "voxray/brickmap/brickmap.hpp"
#include "voxray/brickmap/serialize.hpp"

using namespace voxray;

namespace {

using map = brickmap<std::uint8_t, 8>;
using file_bytes = std::vector<unsigned char>;

std::filesystem::path temp_path(const std::string& name) {
    return std::filesystem::temp_directory_path() / ("voxray_file_" + std::to_string(::getpid()) + "_" + name);
}
file_bytes read_bytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return file_bytes(std::istreambuf_iterator<char>(in), {});
}
void write_bytes(const std::filesystem::path& p, const file_bytes& b) {
    std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}
std::uint64_t file_blob_words(const file_bytes& b) {
    std::uint64_t w;
    std::memcpy(&w, b.data() + 16, 8);
    return w;
}
// The checksum over the header's first 40 bytes, the blob words and what follows.
void reseal(file_bytes& b) {
    fnv64 sum;
    sum.bytes(b.data(), 40);
    std::uint64_t words = file_blob_words(b);
    sum.words(reinterpret_cast<const std::uint32_t*>(b.data() + 48), words);
    sum.bytes(b.data() + 48 + 4 * words, b.size() - 48 - 4 * words);
    std::memcpy(b.data() + 40, &sum.h, 8);
}
void put32(file_bytes& b, std::size_t at, std::uint32_t v) { std::memcpy(b.data() + at, &v, 4); }

std::string load_error(const file_bytes& b, const std::string& name) {
    auto p = temp_path(name);
    write_bytes(p, b);
    std::string what;
    try {
        (void)load_brickmap<map>(p);
    } catch (const error& e) {
        what = e.what();
    }
    std::filesystem::remove(p);
    return what;
}

// The bytes save() writes for m.
file_bytes saved(const map& m, const std::string& name) {
    auto p = temp_path(name);
    save(m, p);
    auto b = read_bytes(p);
    std::filesystem::remove(p);
    return b;
}

voxel_model coloured_model() {
    voxel_model model;
    for (int i = 0; i < 64; ++i) model.set({i, i % 7, 63 - i}, std::uint8_t(1 + i % 9));
    model.palette()[3] = {{10, 20, 30, 255}, {material_kind::metal, 0.2f, 0.9f, 1.5f, 0.0f, 0.0f}};
    model.palette()[9] = {{200, 100, 0, 128}, {material_kind::emit, 0.5f, 0.0f, 1.5f, 40.0f, 0.25f}};
    return model;
}

}  // namespace

TEST(BrickmapFile, PaletteTravelsThroughBuildSaveAndLoad) {
    auto model = coloured_model();
    auto m = map::build(model);
    EXPECT_TRUE(m.palette() == model.palette());
    auto path = temp_path("palette.vxbm");
    save(m, path);
    auto back = load_brickmap<map>(path);
    EXPECT_TRUE(back.palette() == model.palette());
    EXPECT_EQ(back.palette()[9].mat.emission, 40.0f);
    EXPECT_EQ(back.palette()[3].colour.g, 20);
    std::filesystem::remove(path);
}

TEST(BrickmapFile, VersionOneFilesLoadWithTheDefaultPalette) {
    auto m = map::build(coloured_model());
    auto path = temp_path("v1.vxbm");
    auto b = saved(m, "v1_source.vxbm");
    b.resize(48 + 4 * file_blob_words(b));  // version 1 had no palette
    put32(b, 4, 1);
    reseal(b);
    write_bytes(path, b);
    auto back = load_brickmap<map>(path);
    EXPECT_TRUE(back.palette() == palette{});
    EXPECT_TRUE(std::equal(m.blob().begin(), m.blob().end(), back.blob().begin(), back.blob().end()));
    put32(b, 4, 3);
    reseal(b);
    EXPECT_NE(load_error(b, "v3.vxbm").find("unsupported version 3"), std::string::npos);
    std::filesystem::remove(path);
}

TEST(BrickmapFile, BadPaletteRecordIsAnErrorAtItsOffset) {
    auto b = saved(map::build(coloured_model()), "pal.vxbm");
    std::size_t record = 48 + 4 * file_blob_words(b) + 28 * 3;
    float rough = -5.0f;
    std::memcpy(b.data() + record + 8, &rough, 4);
    reseal(b);
    auto what = load_error(b, "pal_bad.vxbm");
    EXPECT_NE(what.find("roughness -5"), std::string::npos) << what;
    EXPECT_NE(what.find("offset " + std::to_string(record + 8)), std::string::npos) << what;
}

TEST(BrickmapFile, ExtentShrunkUnderItsVoxelsIsAnError) {
    voxel_model model;
    model.set({0, 0, 0}, 1);
    model.set({63, 5, 5}, 2);  // on the world's last x layer
    auto m = map::build(model);
    ASSERT_EQ(m.bounds().max.x, 64);
    auto b = saved(m, "extent.vxbm");
    put32(b, 48 + 4 * VX_BM_HEADER_EXTENT, 63);  // same top grid size (8 cells), one voxel less
    reseal(b);
    auto what = load_error(b, "extent_bad.vxbm");
    EXPECT_NE(what.find("outside the world"), std::string::npos) << what;
    // A solid cell on that face: fill the last brick column and collapse it.
    m.fill_box({{56, 0, 0}, {64, 8, 8}}, 4);
    b = saved(m, "extent_solid_source.vxbm");
    put32(b, 48 + 4 * VX_BM_HEADER_EXTENT, 63);
    reseal(b);
    what = load_error(b, "extent_solid.vxbm");
    EXPECT_NE(what.find("outside the world"), std::string::npos) << what;
}

TEST(BrickmapFile, ReservedHeaderWordsMustBeZero) {
    auto b = saved(map::build(coloured_model()), "reserved.vxbm");
    put32(b, 48 + 4 * 27, 7);
    reseal(b);
    auto what = load_error(b, "reserved_bad.vxbm");
    EXPECT_NE(what.find("reserved header word 7"), std::string::npos) << what;
    EXPECT_NE(what.find("blob word 27"), std::string::npos) << what;
}
