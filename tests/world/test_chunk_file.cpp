// Chunk files and the DAG validator: a chunk (real or empty, exact or colour-block
// attributes) round-trips byte for byte; a write leaves no .tmp behind; every flipped
// byte and every truncation is an error naming the file; a file whose checksum is valid
// but whose DAG is structurally bad (pointers out of the region or backwards, wrong
// counts, stray mask bits, a node at two depths, the wrong depth) is refused; and the
// validator accepts every blob the builder makes.
#include <gtest/gtest.h>

#include <bit>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

#include "random_models.hpp"
#include "error_of.hpp"
#include "temp_dir.hpp"
#include "voxray/core/checksum.hpp"
#include "voxray/svdag/builder.hpp"
#include "voxray/svdag/validate.hpp"
#include "voxray/world/build/chunk_dag.hpp"
#include "voxray/world/chunk_file.hpp"

namespace voxray {
namespace {

namespace fs = std::filesystem;
using namespace voxray::test;
using bytes = std::vector<unsigned char>;

// A fresh folder per test, removed at the end.
bytes read_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return bytes(std::istreambuf_iterator<char>(in), {});
}

void write_bytes(const fs::path& p, const bytes& b) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

std::uint32_t get32(const bytes& b, std::size_t at) { std::uint32_t v; std::memcpy(&v, b.data() + at, 4); return v; }
void put32(bytes& b, std::size_t at, std::uint32_t v) { std::memcpy(b.data() + at, &v, 4); }

// Recomputes the checksum field (FNV-1a 64 over bytes 0..71 and the DAG words), so that a
// tampered file reaches the checks behind the checksum.
void reseal(bytes& b) {
    fnv64 sum;
    sum.bytes(b.data(), 72);
    sum.words(reinterpret_cast<const std::uint32_t*>(b.data() + 80), (b.size() - 80) / 4);
    std::memcpy(b.data() + 72, &sum.h, 8);
}


// The message is evaluated once (it may come from error_of).
#define EXPECT_HAS(message, part)                                                                   \
    do {                                                                                            \
        std::string message_ = (message), part_ = (part);                                           \
        EXPECT_NE(message_.find(part_), std::string::npos) << "'" << message_ << "' lacks '" << part_ << "'"; \
    } while (0)

svdag_options attributes(svdag_attributes a) {
    svdag_options o;
    o.attributes = a;
    o.threads = 1;
    return o;
}

// Sparse noise in the chunk's cube, with both corners set so the builder's fitted cube
// is exactly [0, C): origin and shift 0, extent C, depth chunk_bits.
// A palette of distinct colours, so that colour blocks come out many.
voxel_model chunk_model(int bits, int count, std::uint64_t seed) {
    int c = 1 << bits;
    voxel_model m = random_sparse(box3i{glm::ivec3(0), glm::ivec3(c)}, count, seed);
    m.set(glm::ivec3(0), 7);
    m.set(glm::ivec3(c - 1), 200);
    for (int i = 1; i < 256; ++i)
        m.palette()[std::uint8_t(i)].colour = {std::uint8_t(i), std::uint8_t(i * 7), std::uint8_t(i * 13), 255};
    return m;
}

chunk_record make_record(const voxel_model& m, int bits, svdag_attributes a, chunk_key key = {2, {-3, 0, 12}}) {
    chunk_record r;
    r.key = key;
    r.chunk_bits = bits;
    r.solid_min = m.bounds().min;
    r.solid_max = m.bounds().max - 1;
    r.voxel_count = m.voxel_count();
    r.source_hash = 0xC0FFEEu;
    r.dag = svdag_build::build(m, attributes(a)).words;
    return r;
}

// An empty chunk: the builder's empty DAG with the chunk's depth and extent.
chunk_record empty_record(int bits, svdag_attributes a) {
    return build_chunk(chunk_voxels{}, {0, {5, -6, 7}}, bits, chunk_dag_options{a});
}

void expect_same(const chunk_record& a, const chunk_record& b) {
    EXPECT_EQ(a.key, b.key);
    EXPECT_EQ(a.chunk_bits, b.chunk_bits);
    EXPECT_EQ(a.solid_min, b.solid_min);
    EXPECT_EQ(a.solid_max, b.solid_max);
    EXPECT_EQ(a.voxel_count, b.voxel_count);
    EXPECT_EQ(a.source_hash, b.source_hash);
    EXPECT_EQ(a.dag, b.dag);
}

TEST(chunk_file, path_names_lod_and_signed_cell) {
    EXPECT_EQ(chunk_file_path("w", {2, {-3, 0, 12}}), fs::path("w") / "lod2" / "-3_0_12.vxck");
    EXPECT_EQ(chunk_file_path("w", {0, {1, 2, 3}}), fs::path("w") / "lod0" / "1_2_3.vxck");
}

TEST(chunk_file, real_and_empty_chunks_round_trip_byte_for_byte) {
    temp_dir dir;
    std::vector<chunk_record> records;
    for (auto a : {svdag_attributes::exact, svdag_attributes::colour_blocks}) {
        records.push_back(make_record(chunk_model(4, 300, 1), 4, a));
        records.push_back(make_record(chunk_model(6, 5000, 2), 6, a));
        records.push_back(make_record(solid_block(glm::ivec3(0), glm::ivec3(32)), 5, a, {20, {-1, -1, -1}}));
        records.push_back(empty_record(4, a));
        records.push_back(empty_record(10, a));
    }
    for (std::size_t i = 0; i < records.size(); ++i) {
        SCOPED_TRACE("record " + std::to_string(i));
        const chunk_record& r = records[i];
        fs::path p = chunk_file_path(dir.path / "a", r.key), q = dir.path / "b" / "copy.vxck";
        write_chunk_file(p, r);
        EXPECT_EQ(fs::file_size(p), 80 + 4 * r.dag.size());
        chunk_record back = read_chunk_file(p, r.chunk_bits);
        expect_same(r, back);
        write_chunk_file(q, back);
        EXPECT_EQ(read_bytes(p), read_bytes(q));
        EXPECT_NO_THROW(read_chunk_file(q));  // any chunk size
    }
}

TEST(chunk_file, a_write_leaves_no_tmp_and_replaces_old_files) {
    temp_dir dir;
    fs::path p = dir.path / "deep" / "er" / "c.vxck", tmp = p;
    tmp += ".tmp";
    chunk_record a = make_record(chunk_model(4, 100, 3), 4, svdag_attributes::exact);
    write_chunk_file(p, a);  // creates the folders
    EXPECT_TRUE(fs::exists(p));
    EXPECT_FALSE(fs::exists(tmp));
    // A killed writer's leftover .tmp neither hides the real file nor blocks the next write.
    write_bytes(tmp, bytes(13, 0xAB));
    expect_same(read_chunk_file(p), a);
    chunk_record b = make_record(chunk_model(4, 200, 4), 4, svdag_attributes::exact);
    write_chunk_file(p, b);
    EXPECT_FALSE(fs::exists(tmp));
    expect_same(read_chunk_file(p), b);
    // A write that cannot rename (the name is a folder) fails and cleans up its .tmp.
    fs::path folder = dir.path / "taken.vxck", folder_tmp = folder;
    folder_tmp += ".tmp";
    fs::create_directories(folder / "x");
    std::string m = error_of([&] { write_chunk_file(folder, a); });
    EXPECT_HAS(m, folder.string());
    EXPECT_FALSE(fs::exists(folder_tmp));
}

TEST(chunk_file, every_flipped_byte_is_an_error_naming_the_file) {
    temp_dir dir;
    fs::path p = dir.path / "c.vxck";
    write_chunk_file(p, make_record(chunk_model(5, 1500, 5), 5, svdag_attributes::exact));
    const bytes good = read_bytes(p);
    ASSERT_GT(good.size(), 80u + 4 * VX_SV_HEADER_WORDS);
    std::vector<std::size_t> offsets;
    for (std::size_t i = 0; i < 80; ++i) offsets.push_back(i);  // every header byte, checksum included
    for (std::size_t i = 80; i < good.size(); i += 37) offsets.push_back(i);
    offsets.push_back(good.size() - 1);
    for (std::size_t at : offsets) {
        for (unsigned char bit : {0x01, 0x80}) {
            SCOPED_TRACE("byte " + std::to_string(at) + " bit " + std::to_string(bit));
            bytes b = good;
            b[at] ^= bit;
            write_bytes(p, b);
            std::string m = error_of([&] { read_chunk_file(p); });
            EXPECT_HAS(m, p.string());
            EXPECT_HAS(m, "offset ");
        }
    }
}

TEST(chunk_file, truncation_is_an_error_naming_the_size) {
    temp_dir dir;
    fs::path p = dir.path / "c.vxck";
    write_chunk_file(p, make_record(chunk_model(4, 300, 6), 4, svdag_attributes::exact));
    const bytes good = read_bytes(p);
    ASSERT_GT(good.size(), 80u + 4 * VX_SV_HEADER_WORDS);
    for (std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(40), std::size_t(79), std::size_t(80),
                          std::size_t(81), good.size() - 4, good.size() - 1}) {
        write_bytes(p, bytes(good.begin(), good.begin() + std::ptrdiff_t(n)));
        std::string m = error_of([&] { read_chunk_file(p); });
        EXPECT_HAS(m, p.string());
        EXPECT_HAS(m, std::to_string(n) + " bytes");
    }
    bytes longer = good;
    longer.push_back(0);
    write_bytes(p, longer);
    EXPECT_HAS(error_of([&] { read_chunk_file(p); }), std::to_string(longer.size()) + " bytes");
}

// A field set to a wrong value under a valid checksum: the reader names its byte offset.
TEST(chunk_file, wrong_fields_under_a_valid_checksum_are_errors_at_their_offset) {
    temp_dir dir;
    fs::path p = dir.path / "c.vxck";
    write_chunk_file(p, make_record(chunk_model(5, 800, 7), 5, svdag_attributes::exact));
    const bytes good = read_bytes(p);
    ASSERT_GT(good.size(), 80u + 4 * VX_SV_HEADER_WORDS);
    struct field_case {
        std::size_t at;
        std::uint32_t value;
        std::string says;
        std::size_t named = 0;  // the offset the message names, when not `at`
    };
    const std::uint32_t voxels = get32(good, 56), max_x = get32(good, 40), min_y = get32(good, 32);
    std::vector<field_case> cases = {
        {8, 21, "lod 21 is outside [0, 20]"},
        {8, std::uint32_t(-1), "lod -1"},
        {24, 3, "chunk_bits 3 is outside [4, 10]"},
        {24, 11, "chunk_bits 11"},
        {24, 6, "DAG depth 5 (expected 6)", 80 + 4 * VX_SV_HEADER_DEPTH},     // a valid size, but not the DAG's
        {28, std::uint32_t(-1), "solid min -1 is outside [0, 32)"},
        {48, 32, "solid max 32 is outside [0, 32)"},
        // A box inside the chunk but smaller than the DAG's voxels would hide some (issue 22, 14).
        {40, max_x - 1, "solid max " + std::to_string(max_x - 1) + " is not the DAG's voxels' " + std::to_string(max_x)},
        {32, min_y + 1, "solid min " + std::to_string(min_y + 1) + " is not the DAG's voxels' " + std::to_string(min_y)},
        {56, voxels + 1, "does not match the DAG's"},
        {56, 0, "words is outside [24, 74], the most a DAG of 0 voxels in a chunk of 2^5 a side can need", 64},
        {56, 32 * 32 * 32 + 1, "voxel count 32769 is more than the chunk's 32768 voxels"},
        {80 + 4 * VX_SV_HEADER_ORIGIN, 16, "DAG origin 16 (expected 0)"},
        {80 + 4 * (VX_SV_HEADER_SHIFT + 2), 1, "DAG shift 1 (expected 0)"},
        {80 + 4 * (VX_SV_HEADER_EXTENT + 1), 31, "DAG extent 31 (expected 32)"},
    };
    for (auto& c : cases) {
        SCOPED_TRACE(c.says);
        bytes b = good;
        put32(b, c.at, c.value);
        reseal(b);
        write_bytes(p, b);
        std::string m = error_of([&] { read_chunk_file(p); });
        EXPECT_HAS(m, p.string());
        EXPECT_HAS(m, "offset " + std::to_string(c.named ? c.named : c.at) + ":");
        EXPECT_HAS(m, c.says);
    }
    write_bytes(p, good);
    EXPECT_HAS(error_of([&] { read_chunk_file(p, 6); }), "chunk_bits 5 (expected 6");
}

// Word offsets in a builder blob that the structural cases below tamper with.
struct dag_map {
    std::uint32_t root = VX_SV_HEADER_WORDS, node_end, first_child, grandchild, last_slot, root_below_last;
};

dag_map map_of(const blob_words& w) {
    dag_map m;
    m.node_end = VX_SV_HEADER_WORDS + w[VX_SV_HEADER_NODE_WORDS];
    m.first_child = w[m.root + VX_SV_NODE_CHILDREN];
    m.grandchild = w[m.first_child + VX_SV_NODE_CHILDREN];
    const std::uint32_t children = std::uint32_t(std::popcount(w[m.root]));
    m.last_slot = m.root + VX_SV_NODE_CHILDREN + children - 1;
    if (children < 2) throw std::logic_error("the tampered blob's root needs two children");
    m.root_below_last = m.root + VX_SV_NODE_BELOW(children, children - 1);
    return m;
}

struct structure_case {
    const char* name;
    std::function<void(blob_words&, const dag_map&)> tamper;
    const char* says;
};

std::vector<structure_case> structure_cases() {
    return {
        {"pointer past the node region", [](blob_words& w, const dag_map& m) { w[m.root + VX_SV_NODE_CHILDREN] = m.node_end; }, "child pointer"},
        {"pointer past the blob", [](blob_words& w, const dag_map& m) { w[m.root + VX_SV_NODE_CHILDREN] = std::uint32_t(w.size() + 100); }, "outside"},
        {"back pointer (a cycle)", [](blob_words& w, const dag_map& m) { w[m.first_child + VX_SV_NODE_CHILDREN] = m.root; }, "child pointer 24 of the node"},
        {"pointer to itself", [](blob_words& w, const dag_map& m) { w[m.first_child + VX_SV_NODE_CHILDREN] = m.first_child; }, "is outside"},
        {"pointer into the header", [](blob_words& w, const dag_map& m) { w[m.root + VX_SV_NODE_CHILDREN] = 3; }, "child pointer 3"},
        {"node at two depths", [](blob_words& w, const dag_map& m) { w[m.last_slot] = m.grandchild; }, "also at depth"},
        {"wrong voxel count", [](blob_words& w, const dag_map&) { w[VX_SV_HEADER_VOXELS] += 1; }, "in the header is not the nodes'"},
        {"wrong count below a child", [](blob_words& w, const dag_map& m) { w[m.root_below_last] += 1; }, "not its earlier siblings' sum"},
        {"mask bit 9", [](blob_words& w, const dag_map& m) { w[m.root] |= 1u << 9; }, "has bits above bit 7"},
        {"mask bit 8", [](blob_words& w, const dag_map& m) { w[m.first_child] |= 1u << 8; }, "has bits above bit 7"},
        {"empty leaf", [](blob_words& w, const dag_map& m) { w[m.node_end - 2] = w[m.node_end - 1] = 0; }, "leaf has an empty mask"},
        {"empty inner node", [](blob_words& w, const dag_map& m) { w[m.first_child] = 0; }, "empty child mask"},
        {"node region past the blob", [](blob_words& w, const dag_map&) { w[VX_SV_HEADER_NODE_WORDS] = std::uint32_t(w.size()); }, "past the blob"},
        {"node region cut short", [](blob_words& w, const dag_map& m) { w[VX_SV_HEADER_NODE_WORDS] = m.first_child - VX_SV_HEADER_WORDS; }, "outside"},
        {"attributes over the nodes", [](blob_words& w, const dag_map& m) { w[VX_SV_HEADER_ATTRIBUTES] = m.node_end - 1; }, "overlaps the node region"},
        {"attribute count", [](blob_words& w, const dag_map&) { w[VX_SV_HEADER_ATTRIBUTE_COUNT] -= 1; }, "attribute count"},
        {"attribute kind", [](blob_words& w, const dag_map&) { w[VX_SV_HEADER_ATTRIBUTE_KIND] = 2; }, "attribute kind 2 is unknown"},
        {"depth above the limit", [](blob_words& w, const dag_map&) { w[VX_SV_HEADER_DEPTH] = 18; }, "depth 18"},
        {"root pointer", [](blob_words& w, const dag_map& m) { w[VX_SV_HEADER_ROOT] = m.first_child; }, "root pointer"},
        {"blob magic", [](blob_words& w, const dag_map&) { w[VX_SV_HEADER_MAGIC] ^= 1; }, "blob magic"},
    };
}

TEST(svdag_validate, structural_damage_under_a_valid_checksum_is_refused) {
    temp_dir dir;
    fs::path p = dir.path / "c.vxck";
    const chunk_record good = make_record(chunk_model(6, 3000, 8), 6, svdag_attributes::exact);
    const dag_map m = map_of(good.dag);
    ASSERT_GT(std::popcount(good.dag[m.root]), 1);  // the corners: octants 0 and 7
    ASSERT_NO_THROW(validate_svdag_blob(good.dag, "good"));
    for (auto& c : structure_cases()) {
        SCOPED_TRACE(c.name);
        chunk_record r = good;
        c.tamper(r.dag, m);
        std::string direct = error_of([&] { validate_svdag_blob(r.dag, "blob X"); });
        EXPECT_HAS(direct, "blob X: word ");
        EXPECT_HAS(direct, c.says);
        write_chunk_file(p, r);  // the writer seals the checksum over the damage
        std::string m2 = error_of([&] { read_chunk_file(p); });
        EXPECT_HAS(m2, p.string());
        EXPECT_HAS(m2, "(DAG word ");
        EXPECT_HAS(m2, c.says);
    }
    // A depth the chunk does not have: the reader names the DAG's depth word.
    chunk_record r = good;
    r.dag[VX_SV_HEADER_DEPTH] = 7;
    write_chunk_file(p, r);
    EXPECT_HAS(error_of([&] { read_chunk_file(p); }), "offset " + std::to_string(80 + 4 * VX_SV_HEADER_DEPTH));
    // The validator alone walks it with the wrong leaf depth and finds the damage.
    EXPECT_HAS(error_of([&] { validate_svdag_blob(r.dag, "deeper"); }), "deeper: word ");
    r.dag[VX_SV_HEADER_DEPTH] = 5;
    EXPECT_HAS(error_of([&] { validate_svdag_blob(r.dag, "shallower"); }), "shallower: word ");
}

TEST(svdag_validate, colour_block_damage_is_refused) {
    const blob_words good = make_record(chunk_model(6, 3000, 9), 6, svdag_attributes::colour_blocks).dag;
    ASSERT_NO_THROW(validate_svdag_blob(good, "good"));
    const std::uint32_t starts = good[VX_SV_HEADER_ATTRIBUTES], n = good[VX_SV_HEADER_ATTRIBUTE_COUNT];
    ASSERT_GE(n, 3u);
    auto refused = [&](std::function<void(blob_words&)> tamper, const char* says) {
        blob_words w = good;
        tamper(w);
        EXPECT_HAS(error_of([&] { validate_svdag_blob(w, "blocks"); }), says);
    };
    refused([&](blob_words& w) { w[starts] = 1; }, "first colour block starts at 1");
    refused([&](blob_words& w) { w[starts + 2] = w[starts + 1]; }, "is not above the previous start");
    refused([&](blob_words& w) { w[starts + n - 1] = w[VX_SV_HEADER_VOXELS]; }, "is not below the voxel count");
    refused([&](blob_words& w) { w[VX_SV_HEADER_SEARCH_TOP] += 1; }, "search top");
    refused([&](blob_words& w) { w[VX_SV_HEADER_COLOURS] = starts + 1; }, "overlap the");
    refused([&](blob_words& w) { w[VX_SV_HEADER_COLOURS] = std::uint32_t(w.size() - n + 1); }, "past the blob");
    refused([&](blob_words& w) { w[VX_SV_HEADER_ATTRIBUTE_COUNT] = 0, w[VX_SV_HEADER_SEARCH_TOP] = 0; }, "no colour blocks for");
}

TEST(svdag_validate, short_blobs_are_refused) {
    EXPECT_HAS(error_of([] { validate_svdag_blob({}, "nothing"); }), "nothing: word 0: blob of 0 words");
    blob_words w = svdag_build::build(voxel_model{}, {}).words;
    w.resize(VX_SV_HEADER_WORDS);  // the root's words are gone
    EXPECT_HAS(error_of([&] { validate_svdag_blob(w, "cut"); }), "past the blob");
    w[VX_SV_HEADER_NODE_WORDS] = 0;
    w[VX_SV_HEADER_ATTRIBUTES] = VX_SV_HEADER_WORDS;
    EXPECT_HAS(error_of([&] { validate_svdag_blob(w, "cut"); }), "past the node region's end");
}

TEST(svdag_validate, accepts_every_blob_the_builder_makes) {
    std::vector<voxel_model> models;
    models.push_back(random_sparse(box3i{{-200, -7, 60}, {100, 90, 300}}, 20000, 10));
    models.push_back(random_model(40, 0.3f, 11, {-21, 5, -3}));
    models.push_back(solid_block(glm::ivec3(0), glm::ivec3(64)));
    models.push_back(patterned_block(glm::ivec3(-5), glm::ivec3(27)));
    models.push_back(voxel_model{});
    models.push_back(single_voxel({3, -9, 100}));
    models.push_back(hollow_box(50, {-20, 0, 0}));
    for (std::size_t i = 0; i < models.size(); ++i)
        for (auto a : {svdag_attributes::exact, svdag_attributes::colour_blocks}) {
            blob_words w = svdag_build::build(models[i], attributes(a)).words;
            EXPECT_NO_THROW(validate_svdag_blob(w, "model " + std::to_string(i))) << "model " << i;
        }
}

}  // namespace
}  // namespace voxray
