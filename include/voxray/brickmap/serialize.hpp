// Brickmap files: a 48-byte header, the blob words exactly as in memory (so a load gives
// a bit-identical blob), then the palette. Everything little endian.
//
//   offset  size  field
//        0     4  magic "VXBF" (0x46425856)
//        4     4  file version (2; version 1 files, without a palette, still load
//                 with the default palette)
//        8     4  payload bits (8, 16, 32)      must match the brickmap type
//       12     4  brick edge (4, 8, 16)         must match the brickmap type
//       16     8  blob words                    file size must be 48 + 4 * words (+ 7168)
//       24     8  solid voxel count             checked against the content
//       32     4  bricks used (pool high-water mark)
//       36     4  pages used
//       40     8  checksum: FNV-1a 64 over bytes 0..39, every blob word, the palette
//       48        blob words
//   48 + 4w 7168  palette: 256 records of 28 bytes (io/palette_record.hpp)
//
// A load trusts nothing: sizes are checked before anything is allocated, the checksum
// before the content is parsed, and the content (layout offsets, page and brick
// references, occupancy vs payload, counts) before the brickmap is handed out. Every
// failure is a voxray::error naming the file, the byte offset and the value.
#pragma once
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "voxray/brickmap/brickmap.hpp"
#include "voxray/core/checksum.hpp"
#include "voxray/io/palette_record.hpp"

namespace voxray {

static_assert(std::endian::native == std::endian::little, "brickmap files assume a little-endian host");

inline constexpr std::uint32_t brickmap_file_magic = 0x46425856u;  // "VXBF"
inline constexpr std::uint32_t brickmap_file_version = 2;
inline constexpr std::size_t brickmap_file_header_bytes = 48;

template <class Payload, int E>
struct brickmap_io {
    using map = brickmap<Payload, E>;
    using codec = typename map::codec;

    // Safe while other threads edit: the blob and its counts are copied under the
    // exclusive lock (writers wait for a memcpy, not for the disk), then written.
    static void save(const map& m, const std::filesystem::path& path) {
        auto frame = m.snapshot();
        blob_words words(frame.blob.begin(), frame.blob.end());
        std::uint32_t bricks_used = m.pool_.used(), pages_used = m.page_used_;
        std::vector<unsigned char> pal = io::encode_palette(m.palette_);
        frame.lock.unlock();
        unsigned char h[brickmap_file_header_bytes] = {};
        auto put32 = [&](std::size_t at, std::uint32_t v) { std::memcpy(h + at, &v, 4); };
        auto put64 = [&](std::size_t at, std::uint64_t v) { std::memcpy(h + at, &v, 8); };
        put32(0, brickmap_file_magic);
        put32(4, brickmap_file_version);
        put32(8, codec::payload_bits);
        put32(12, E);
        put64(16, words.size());
        put64(24, frame.voxels);
        put32(32, bricks_used);
        put32(36, pages_used);
        fnv64 sum;
        sum.bytes(h, 40);
        sum.words(words.data(), words.size());
        sum.bytes(pal.data(), pal.size());
        put64(40, sum.h);
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        if (!out) fail("brickmap file ", path.string(), ": cannot open for writing");
        out.write(reinterpret_cast<const char*>(h), sizeof h);
        out.write(reinterpret_cast<const char*>(words.data()), std::streamsize(words.size() * 4));
        out.write(reinterpret_cast<const char*>(pal.data()), std::streamsize(pal.size()));
        if (!out) fail("brickmap file ", path.string(), ": write failed");
    }

    static map load(const std::filesystem::path& path) {
        std::string name = path.string();
        std::error_code ec;
        std::uint64_t size = std::filesystem::file_size(path, ec);
        if (ec) fail("brickmap file ", name, ": cannot read (", ec.message(), ")");
        if (size < brickmap_file_header_bytes)
            fail("brickmap file ", name, ": offset 0: truncated, ", size, " bytes is shorter than the ",
                 brickmap_file_header_bytes, "-byte header");
        std::ifstream in(path, std::ios::binary);
        unsigned char h[brickmap_file_header_bytes];
        if (!in.read(reinterpret_cast<char*>(h), sizeof h)) fail("brickmap file ", name, ": cannot read the header");
        auto get32 = [&](std::size_t at) { std::uint32_t v; std::memcpy(&v, h + at, 4); return v; };
        auto get64 = [&](std::size_t at) { std::uint64_t v; std::memcpy(&v, h + at, 8); return v; };
        auto bad = [&](std::uint64_t offset, const char* what, std::uint64_t value, auto... more) {
            fail("brickmap file ", name, ": offset ", offset, ": ", what, " ", value, more...);
        };
        if (get32(0) != brickmap_file_magic) bad(0, "bad magic", get32(0), " (expected ", brickmap_file_magic, ")");
        const std::uint32_t version = get32(4);
        if (version != 1 && version != brickmap_file_version)
            bad(4, "unsupported version", version, " (this build reads versions 1 and ", brickmap_file_version, ")");
        const std::uint64_t palette_size = version >= 2 ? io::palette_bytes : 0;
        if (get32(8) != codec::payload_bits)
            bad(8, "payload bits", get32(8), " do not match this brickmap's ", codec::payload_bits);
        if (get32(12) != std::uint32_t(E)) bad(12, "brick edge", get32(12), " does not match this brickmap's ", E);
        std::uint64_t words = get64(16);
        if (words < VX_BM_HEADER_WORDS || words >= max_blob_words)
            bad(16, "blob size of", words, " words is outside [", VX_BM_HEADER_WORDS, ", ", max_blob_words, ")");
        if (size != brickmap_file_header_bytes + 4 * words + palette_size)
            bad(16, "blob size of", words, " words needs a file of ", brickmap_file_header_bytes + 4 * words + palette_size,
                " bytes (version ", version, "), but the file has ", size, " (truncated or trailing data)");
        blob_words blob(words);
        if (!in.read(reinterpret_cast<char*>(blob.data()), std::streamsize(words * 4)))
            fail("brickmap file ", name, ": cannot read ", words * 4, " bytes of blob");
        std::vector<unsigned char> pal(palette_size);
        if (palette_size && !in.read(reinterpret_cast<char*>(pal.data()), std::streamsize(palette_size)))
            fail("brickmap file ", name, ": cannot read the ", palette_size, "-byte palette");
        fnv64 sum;
        sum.bytes(h, 40);
        sum.words(blob.data(), blob.size());
        sum.bytes(pal.data(), pal.size());
        if (sum.h != get64(40)) bad(40, "checksum", get64(40), " does not match the content's ", sum.h);
        map m = restore(std::move(blob), get64(24), get32(32), get32(36), name);
        if (palette_size) m.palette_ = io::decode_palette(pal.data(), "brickmap file " + name, 48 + 4 * words);
        return m;
    }

    // Calls bad(index) for the first solid voxel whose in-brick coordinate is not below
    // `inside` on every axis.
    template <class Bad>
    static void check_outside_empty(const std::uint32_t* brick, glm::uvec3 inside, Bad&& bad) {
        for (unsigned z = 0; z < unsigned(E); ++z)
            for (unsigned y = 0; y < unsigned(E); ++y)
                for (unsigned x = 0; x < unsigned(E); ++x) {
                    if (x < inside.x && y < inside.y && z < inside.z) continue;
                    std::uint32_t index = codec::index(x, y, z);
                    if (codec::get(brick, index) != 0) bad(index);
                }
    }

    // Checks a blob's layout and content and rebuilds the host-side state around it.
    static map restore(blob_words blob, std::uint64_t voxels, std::uint32_t bricks_used, std::uint32_t pages_used,
                       const std::string& name) {
        const std::uint64_t base = brickmap_file_header_bytes;
        auto bad = [&](std::uint64_t word, const char* what, std::uint64_t value, auto... more) {
            fail("brickmap file ", name, ": offset ", base + 4 * word, " (blob word ", word, "): ", what, " ", value,
                 more...);
        };
        auto expect = [&](std::uint32_t word, std::uint64_t want, const char* what) {
            if (blob[word] != want) bad(word, what, blob[word], " (expected ", want, ")");
        };
        expect(VX_BM_HEADER_MAGIC, VX_BM_MAGIC, "blob magic");
        expect(VX_BM_HEADER_VERSION, VX_BM_VERSION, "blob layout version");
        expect(VX_BM_HEADER_BRICK_BITS, codec::bits, "brick bits");
        expect(VX_BM_HEADER_PAYLOAD_BITS, codec::payload_bits, "payload bits");
        expect(VX_BM_HEADER_BRICK_WORDS, codec::words, "brick words");
        expect(VX_BM_HEADER_OCCUPANCY_WORDS, codec::occupancy_words, "occupancy words");
        for (std::uint32_t r = VX_BM_HEADER_BRICK_CAPACITY + 1; r < VX_BM_HEADER_WORDS; ++r)
            expect(r, 0, "reserved header word");
        box3i world;
        for (int a = 0; a < 3; ++a) {
            auto o = std::int32_t(blob[VX_BM_HEADER_ORIGIN + a]);
            std::uint32_t e = blob[VX_BM_HEADER_EXTENT + a];
            if (std::int64_t(o) + e > std::numeric_limits<int>::max())
                bad(VX_BM_HEADER_EXTENT + a, "world extent", e, " overflows 32-bit coordinates");
            world.min[a] = o;
            world.max[a] = int(std::int64_t(o) + e);
        }
        std::uint64_t edge = E, table = 1;
        for (int a = 0; a < 3; ++a) {
            std::uint64_t cells = (std::uint64_t(blob[VX_BM_HEADER_EXTENT + a]) + edge - 1) / edge;
            expect(VX_BM_HEADER_CELLS + a, cells, "top grid size");
            std::uint64_t pages = (cells + VX_BM_PAGE_MASK) / VX_BM_PAGE_EDGE;
            expect(VX_BM_HEADER_PAGES_DIM + a, pages, "page table size");
            table *= pages;
            if (table >= max_blob_words)
                bad(VX_BM_HEADER_EXTENT + a, "world extent", blob[VX_BM_HEADER_EXTENT + a], " needs a page table above the blob limit");
        }
        std::uint64_t page_cap = blob[VX_BM_HEADER_PAGE_CAPACITY], brick_cap = blob[VX_BM_HEADER_BRICK_CAPACITY];
        expect(VX_BM_HEADER_PAGE_TABLE, VX_BM_HEADER_WORDS, "page table offset");
        expect(VX_BM_HEADER_PAGES, VX_BM_HEADER_WORDS + table, "page pool offset");
        std::uint64_t bricks_off = VX_BM_HEADER_WORDS + table + page_cap * VX_BM_PAGE_WORDS;
        expect(VX_BM_HEADER_BRICKS, bricks_off, "brick pool offset");
        if (bricks_off + brick_cap * codec::words != blob.size())
            bad(VX_BM_HEADER_BRICK_CAPACITY, "brick capacity", brick_cap, " does not fill the blob of ", blob.size(),
                " words");
        if (pages_used > page_cap || pages_used > std::max<std::uint64_t>(table, 1))
            fail("brickmap file ", name, ": offset 36: pages used ", pages_used, " above the capacity ", page_cap);
        if (bricks_used > brick_cap)
            fail("brickmap file ", name, ": offset 32: bricks used ", bricks_used, " above the capacity ", brick_cap);

        map m(world, {std::uint32_t(brick_cap), std::uint32_t(page_cap)});
        if (m.words_.size() != blob.size()) bad(0, "layout of", blob.size(), " words is inconsistent");
        m.words_ = std::move(blob);
        const auto& w = m.words_;
        std::vector<bool> page_seen(pages_used), brick_seen(bricks_used);
        std::uint64_t count = 0;
        std::uint32_t pages_off = VX_BM_HEADER_WORDS + std::uint32_t(table);
        for (std::uint32_t s = 0; s < table; ++s) {
            std::uint32_t slot = VX_BM_HEADER_WORDS + s;
            std::uint32_t page = w[slot];
            if (page == VX_BM_EMPTY_PAGE) continue;
            if (page >= pages_used) bad(slot, "page index", page, " is not below the pages used, ", pages_used);
            if (page_seen[page]) bad(slot, "page", page, " is referenced twice");
            page_seen[page] = true;
            glm::uvec3 pc{s % m.pages_dim_.x, (s / m.pages_dim_.x) % m.pages_dim_.y, s / m.pages_dim_.x / m.pages_dim_.y};
            for (std::uint32_t l = 0; l < VX_BM_PAGE_WORDS; ++l) {
                std::uint32_t co = pages_off + page * VX_BM_PAGE_WORDS + l;
                std::uint32_t c = w[co];
                if (!c) continue;
                glm::uvec3 cell = pc * 16u + glm::uvec3(l & 15, (l >> 4) & 15, l >> 8);
                if (cell.x >= m.cells_.x || cell.y >= m.cells_.y || cell.z >= m.cells_.z)
                    bad(co, "top cell outside the world holds", c, "");
                // A cell on the world's far faces covers voxels outside the world: those
                // must be empty (a solid cell there, or set bits, would count them).
                glm::uvec3 inside = glm::min(glm::uvec3(E), glm::uvec3(world.extent()) - cell * unsigned(E));
                bool edge_cell = inside != glm::uvec3(E);
                if (!(c & VX_BM_CELL_IS_BRICK)) {
                    if (VX_BM_CELL_VALUE(c) > codec::value_mask) bad(co, "solid cell payload", VX_BM_CELL_VALUE(c), " is too wide");
                    if (edge_cell) bad(co, "solid cell", c, " covers voxels outside the world");
                    count += map::full;
                    continue;
                }
                std::uint32_t b = VX_BM_CELL_VALUE(c);
                if (b >= bricks_used) bad(co, "brick index", b, " is not below the bricks used, ", bricks_used);
                if (brick_seen[b]) bad(co, "brick", b, " is referenced twice");
                brick_seen[b] = true;
                const std::uint32_t* brick = w.data() + bricks_off + std::uint64_t(b) * codec::words;
                std::uint32_t bad_word = codec::first_inconsistent_word(brick);
                if (bad_word != codec::words)
                    bad(bricks_off + std::uint64_t(b) * codec::words + bad_word, "payload word", brick[bad_word],
                        " disagrees with the occupancy bits of brick ", b);
                if (edge_cell) check_outside_empty(brick, inside, [&](std::uint32_t index) {
                    bad(bricks_off + std::uint64_t(b) * codec::words, "brick", b, " has voxel ", index,
                        " outside the world (extent ", world.extent().x, " x ", world.extent().y, " x ",
                        world.extent().z, ")");
                });
                std::uint32_t n = codec::count(brick);
                m.meta_[b] = n;
                m.owner_[b] = co;
                count += n;
            }
        }
        // Unreferenced pages and bricks must be zero: they are handed out as empty.
        for (std::uint64_t p = 0; p < page_cap; ++p) {
            if (p < pages_used && page_seen[p]) continue;
            for (std::uint64_t i = pages_off + p * VX_BM_PAGE_WORDS, e = i + VX_BM_PAGE_WORDS; i < e; ++i)
                if (w[i]) bad(i, "unused page word holds", w[i], "");
        }
        std::vector<std::uint32_t> free_list;
        for (std::uint64_t b = 0; b < brick_cap; ++b) {
            if (b < bricks_used && brick_seen[b]) continue;
            for (std::uint64_t i = bricks_off + b * codec::words, e = i + codec::words; i < e; ++i)
                if (w[i]) bad(i, "unused brick word holds", w[i], "");
            if (b < bricks_used) free_list.push_back(std::uint32_t(b));
        }
        if (count != voxels)
            fail("brickmap file ", name, ": offset 24: voxel count ", voxels, " does not match the content's ", count);
        m.pool_.restore(std::uint32_t(brick_cap), bricks_used, free_list);
        m.page_used_ = pages_used;
        m.voxel_count_ = std::int64_t(count);
        m.dirty_.mark_whole();
        return m;
    }
};

template <class Payload, int E>
void save(const brickmap<Payload, E>& m, const std::filesystem::path& path) {
    brickmap_io<Payload, E>::save(m, path);
}
template <class Map>
Map load_brickmap(const std::filesystem::path& path) {
    return brickmap_io<typename Map::payload_type, Map::brick_edge>::load(path);
}

}  // namespace voxray
