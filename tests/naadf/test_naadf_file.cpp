// NAADF files: an edited structure saved and loaded is the same blob, voxels, palette
// and count, and stays editable (storage bookkeeping restored from the cells); every kind
// of damage is rejected with an error naming the file offset: truncation, a flipped
// byte, and content that passes the checksum but breaks the layout's rules.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "naadf_cells.hpp"
#include "random_models.hpp"
#include "voxray/check/random_edits.hpp"
#include "voxray/cpu.hpp"
#include "voxray/naadf/serialize.hpp"
#include "voxray/tracer.hpp"

namespace voxray::test {
namespace {

std::filesystem::path temp_file(const std::string& name) {
    return std::filesystem::temp_directory_path() / ("voxray_naadf_" + std::to_string(::getpid()) + "_" + name);
}

std::vector<unsigned char> read_bytes(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), {}};
}
void write_bytes(const std::filesystem::path& p, const std::vector<unsigned char>& b) {
    std::ofstream(p, std::ios::binary).write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
}

// The file's checksum recomputed, so that a content check (not the checksum) must catch it.
void reseal(std::vector<unsigned char>& b) {
    fnv64 sum;
    sum.bytes(b.data(), 24);
    sum.words(reinterpret_cast<const std::uint32_t*>(b.data() + naadf_file_header_bytes), (b.size() - naadf_file_header_bytes - io::palette_bytes) / 4);
    sum.bytes(b.data() + b.size() - io::palette_bytes, io::palette_bytes);
    std::memcpy(b.data() + 24, &sum.h, 8);
}

std::uint32_t& blob_word(std::vector<unsigned char>& b, std::uint64_t word) {
    return *reinterpret_cast<std::uint32_t*>(b.data() + naadf_file_header_bytes + 4 * word);
}

void expect_rejected(const std::vector<unsigned char>& bytes, const std::string& needle, const std::string& what) {
    auto path = temp_file("bad.vxna");
    write_bytes(path, bytes);
    try {
        load_naadf(path);
        ADD_FAILURE() << what << ": loaded";
    } catch (const error& e) {
        std::string m = e.what();
        EXPECT_NE(m.find("offset"), std::string::npos) << what << ": " << m;
        EXPECT_NE(m.find(needle), std::string::npos) << what << ": " << m;
    }
    std::filesystem::remove(path);
}

// An edited structure: free lists, shared groups, a grown world.
naadf edited_structure(voxel_model& model) {
    model = random_model(50, 0.1f, 21, {240, 0, 0});
    model.palette()[7].colour = {0x11, 0x22, 0x33, 0x44};
    naadf s(model);
    box3i world = s.bounds();
    for (auto& e : random_edits(world, 60, 22)) {
        std::visit([&](const auto& r) { s.apply(r, e.op, naadf::payload_type(e.value)); }, e.region);
        apply_to_model(model, e, world);
    }
    s.fill_sphere({100, 10, 10}, 4, 9);  // grows the world
    model.set({100, 10, 10}, 9);
    apply_to_model(model, {regions::sphere{{100, 10, 10}, 4}, edit_op::fill, 9}, world);
    return s;
}

TEST(naadf_file, save_then_load_gives_the_same_structure_and_it_stays_editable) {
    voxel_model model;
    naadf s = edited_structure(model);
    auto path = temp_file("round.vxna");
    save(s, path);
    naadf loaded = load_naadf(path);
    std::filesystem::remove(path);
    ASSERT_EQ(loaded.blob().size(), s.blob().size());
    EXPECT_TRUE(std::equal(s.blob().begin(), s.blob().end(), loaded.blob().begin()));
    EXPECT_EQ(loaded.voxel_count(), model.voxel_count());
    EXPECT_EQ(loaded.bounds().min, s.bounds().min);
    EXPECT_EQ(loaded.bounds().max, s.bounds().max);
    EXPECT_TRUE(loaded.palette()[7].colour == (rgba{0x11, 0x22, 0x33, 0x44}));
    EXPECT_EQ(loaded.stats().groups, s.stats().groups);
    EXPECT_EQ(loaded.stats().mixed_chunks, s.stats().mixed_chunks);
    // The same edits on both: the same voxels, and storage in use stays exact.
    auto edits = random_edits(s.bounds(), 40, 23);
    for (naadf* x : {&s, &loaded})
        for (auto& e : edits) std::visit([&](const auto& r) { x->apply(r, e.op, naadf::payload_type(e.value)); }, e.region);
    for (auto& e : edits) apply_to_model(model, e, s.bounds());
    loaded.refine();
    expect_cells_match(loaded.blob(), model, model.bounds(), "loaded and edited");
    EXPECT_EQ(loaded.stats().groups, naadf(model).stats().groups);
    EXPECT_EQ(loaded.stats().mixed_chunks, naadf(model).stats().mixed_chunks);
}

// The bytes of an edited structure's file.
std::vector<unsigned char> edited_file() {
    voxel_model model;
    auto path = temp_file("good.vxna");
    save(edited_structure(model), path);
    auto bytes = read_bytes(path);
    std::filesystem::remove(path);
    return bytes;
}

TEST(naadf_file, damaged_files_are_rejected_with_the_offset) {
    const auto good = edited_file();
    const std::uint64_t words = (good.size() - naadf_file_header_bytes - io::palette_bytes) / 4;
    auto w = [&](std::uint64_t i) { return *reinterpret_cast<const std::uint32_t*>(good.data() + naadf_file_header_bytes + 4 * i); };

    expect_rejected({good.begin(), good.begin() + 20}, "shorter than", "header cut");
    expect_rejected({good.begin(), good.end() - 1}, "needs", "one byte short");
    auto flipped = good;
    flipped[naadf_file_header_bytes + 4 * (words / 2)] ^= 0x10;
    expect_rejected(flipped, "checksum", "flipped byte");

    // Resealed damage: the content checks must see it.
    struct damage {
        const char* what;
        const char* needle;
        std::function<void(std::vector<unsigned char>&)> apply;
    };
    const std::uint32_t table = w(VX_NA_HEADER_PAGE_TABLE);
    const std::uint32_t chunks = w(VX_NA_HEADER_CHUNKS), blocks = w(VX_NA_HEADER_BLOCKS);
    // The first mixed page's chunk array, its first mixed chunk's block array.
    std::uint32_t mixed_page = 0;
    while (VX_NA_STATE(w(table + mixed_page)) != VX_NA_MIXED) ++mixed_page;
    std::uint64_t array = chunks + std::uint64_t(VX_NA_PAYLOAD(w(table + mixed_page))) * VX_NA_CHUNK_ARRAY_WORDS;
    std::uint32_t mixed_chunk = 0, empty_chunk = 0;
    while (VX_NA_STATE(w(array + mixed_chunk)) != VX_NA_MIXED) ++mixed_chunk;
    while (VX_NA_STATE(w(array + empty_chunk)) != VX_NA_EMPTY || w(array + empty_chunk) == 0) ++empty_chunk;
    std::uint64_t barray = blocks + std::uint64_t(VX_NA_PAYLOAD(w(array + mixed_chunk))) * VX_NA_BLOCK_ARRAY_WORDS;
    damage cases[] = {
        {"voxel count", "voxel count", [](auto& b) { b[16] ^= 1; }},
        {"blob magic", "blob magic", [&](auto& b) { blob_word(b, VX_NA_HEADER_MAGIC) ^= 1; }},
        {"reserved header word", "reserved", [&](auto& b) { blob_word(b, VX_NA_HEADER_WORDS - 1) = 5; }},
        {"world cut to 10 voxels", "", [&](auto& b) { blob_word(b, VX_NA_HEADER_EXTENT) = 10; }},
        {"extent overflow", "overflows", [&](auto& b) { blob_word(b, VX_NA_HEADER_EXTENT + 1) = 0xFFFFFFF0u; }},
        {"world too big for a page table", "page table", [&](auto& b) {
             for (int a = 0; a < 3; ++a) blob_word(b, VX_NA_HEADER_EXTENT + a) = 0x40000000u;
         }},
        {"area offset", "offset", [&](auto& b) { blob_word(b, VX_NA_HEADER_BLOCKS) += 64; }},
        {"state 3", "state 3", [&](auto& b) { blob_word(b, table + mixed_page) |= 3u << 30; }},
        {"index out of range", "points to array", [&](auto& b) { blob_word(b, array + mixed_chunk) = VX_NA_MIXED_CELL(0x3FFFFFF0u); }},
        {"shared block array", "shares block array", [&](auto& b) { blob_word(b, array + empty_chunk) = w(array + mixed_chunk); }},
        {"type 0", "type", [&](auto& b) { blob_word(b, array + mixed_chunk) = VX_NA_UNIFORM_CELL(0u); }},
        {"field into solid", "field", [&](auto& b) { blob_word(b, array + empty_chunk) = 0x3FFFFFFFu; }},
        {"block field into solid", "field", [&](auto& b) {
             std::uint32_t e = 0;
             while (VX_NA_STATE(w(barray + e)) != VX_NA_EMPTY) ++e;
             blob_word(b, barray + e) = 0xFFFu;  // reaches 3 blocks every way: into the solid one or out of the chunk
         }},
    };
    for (auto& d : cases) {
        auto bytes = good;
        d.apply(bytes);
        reseal(bytes);
        expect_rejected(bytes, d.needle, d.what);
    }
}

// Random words of a valid file replaced and the checksum recomputed: every load either
// gives a structure that traces (and edits) like any other, or a voxray::error. Under
// ASan + UBSan this is where a missed check would show as a bad read.
TEST(naadf_file, random_damage_loads_cleanly_or_is_rejected) {
    const auto good = edited_file();
    auto path = temp_file("fuzz.vxna");
    const std::uint64_t words = (good.size() - naadf_file_header_bytes - io::palette_bytes) / 4;
    rng g(99);
    int loaded = 0, rejected = 0;
    for (int n = 0; n < 200; ++n) {
        auto bytes = good;
        // Mostly the header and the cells (where the structure is), sometimes anywhere.
        std::uint64_t word = g.below(4) ? g.below(std::uint32_t(std::min<std::uint64_t>(words, 20000))) : g.below(std::uint32_t(words));
        std::uint32_t values[] = {0u, 1u, 0xFFFFFFFFu, 0x80000000u | g.below(1u << 30), 0x40000000u | g.below(300),
                                  std::uint32_t(g.below(1u << 30)), blob_word(bytes, word) ^ (1u << g.below(32))};
        blob_word(bytes, word) = values[g.below(7)];
        reseal(bytes);
        write_bytes(path, bytes);
        try {
            naadf x = load_naadf(path);
            ++loaded;
            auto rays = random_rays(x.bounds(), 200, std::uint64_t(n));
            std::vector<hit> hits(rays.size());
            tracer<cpu, naadf>(x).closest_hit(rays, hits);
            x.fill_sphere(x.bounds().min + 5, 4, 3);
            x.refine();
        } catch (const error&) {
            ++rejected;
        }
    }
    std::filesystem::remove(path);
    std::printf("random damage: %d loaded, %d rejected\n", loaded, rejected);
    EXPECT_GT(rejected, 60);
}

}  // namespace
}  // namespace voxray::test
