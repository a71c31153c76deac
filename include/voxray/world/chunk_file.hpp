// Chunk files (.vxck): one chunk of the open world per file, a sparse voxel DAG
// (svdag/layout.h) over the chunk's fixed cube of C = 2^chunk_bits voxels a side, so the
// DAG's depth is chunk_bits, its origin and shift 0 and its extent C. Little endian.
//
//   offset  size  field
//        0     4  magic "VXCK" (0x4b435856)
//        4     4  file version (1)
//        8     4  lod                           [0, 20]
//       12    12  cell x, y, z (signed)         the chunk's place in the grid of its LOD
//       24     4  chunk_bits                    [4, 10]; the DAG's depth
//       28    12  solid min x, y, z (signed)    inclusive box of the solid voxels, in [0, C)
//       40    12  solid max x, y, z (signed)    or empty (max < min on an axis) when no voxels
//       52     4  source hash                   opaque to the reader (resume compares it)
//       56     8  solid voxel count             == the DAG's (its header's)
//       64     8  DAG words                     file size must be 80 + 4 * words
//       72     8  checksum: FNV-1a 64 over bytes 0..71 and every DAG word
//       80        DAG words (svdag/layout.h)
//
// The files are untrusted: a GPU kernel walks the DAG's pointers. A read checks the sizes
// (the DAG's against what its voxel count can need, the file's against the DAG's) before
// anything is allocated, the checksum before the content is parsed, then every field,
// the DAG's structure (svdag/validate.hpp) and its solid box against its voxels. Every
// failure is a voxray::error naming the file, the byte offset and the value. A write
// goes to path + ".tmp" and is renamed into place, so a killed writer never leaves a
// half file under the real name.
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <system_error>
#include <unordered_map>

#include <glm/vec3.hpp>

#include "voxray/core/blob.hpp"
#include "voxray/core/checksum.hpp"
#include "voxray/core/error.hpp"
#include "voxray/svdag/layout.h"
#include "voxray/svdag/validate.hpp"
#include "voxray/world/chunk.hpp"

namespace voxray {

static_assert(std::endian::native == std::endian::little, "chunk files assume a little-endian host");

inline constexpr std::uint32_t chunk_file_magic = 0x4b435856u;  // "VXCK"
inline constexpr std::uint32_t chunk_file_version = 1;
inline constexpr std::size_t chunk_file_header_bytes = 80;
inline constexpr int chunk_min_bits = VX_WD_MIN_CHUNK_BITS, chunk_max_bits = VX_WD_MAX_CHUNK_BITS;
inline constexpr int chunk_max_lod = VX_WD_MAX_LOD;

namespace chunk_file_offset {
inline constexpr std::size_t magic = 0, version = 4, lod = 8, cell = 12, chunk_bits = 24, solid_min = 28,
                             solid_max = 40, source_hash = 52, voxel_count = 56, dag_words = 64, checksum = 72;
}

// dir/lod<l>/<x>_<y>_<z>.vxck; negative cells keep their sign ("lod0/-3_0_12.vxck").
inline std::filesystem::path chunk_file_path(const std::filesystem::path& dir, const chunk_key& k) {
    return dir / ("lod" + std::to_string(k.lod)) /
           (std::to_string(k.cell.x) + "_" + std::to_string(k.cell.y) + "_" + std::to_string(k.cell.z) + ".vxck");
}

namespace chunk_file_detail {

inline void put32(unsigned char* h, std::size_t at, std::uint32_t v) { std::memcpy(h + at, &v, 4); }
inline void put64(unsigned char* h, std::size_t at, std::uint64_t v) { std::memcpy(h + at, &v, 8); }
inline std::uint32_t get32(const unsigned char* h, std::size_t at) { std::uint32_t v; std::memcpy(&v, h + at, 4); return v; }
inline std::uint64_t get64(const unsigned char* h, std::size_t at) { std::uint64_t v; std::memcpy(&v, h + at, 8); return v; }

inline std::uint64_t checksum(const unsigned char* header, const blob_words& dag) {
    fnv64 sum;
    sum.bytes(header, chunk_file_offset::checksum);
    sum.words(dag.data(), dag.size());
    return sum.h;
}

// The most words a chunk's DAG can need for its voxel count: the header, at most
// min(8^d, voxels) nodes of up to 16 words on each interior level d, as many leaves of 2
// words on the leaf level, and 2 words of attributes a voxel (colour blocks' start and
// colour; exact payloads need a quarter). A size past it is a lie, refused before
// anything is allocated for it.
inline std::uint64_t dag_word_limit(int chunk_bits, std::uint64_t voxels) {
    std::uint64_t words = VX_SV_HEADER_WORDS + 2 * voxels, level = 1, nodes = std::max<std::uint64_t>(voxels, 1);
    for (int d = 0; d <= chunk_bits - VX_SV_LEAF_EDGE_BITS; ++d, level *= 8)
        words += (d < chunk_bits - VX_SV_LEAF_EDGE_BITS ? VX_SV_NODE_WORDS(8) : VX_SV_LEAF_WORDS) * std::min(level, nodes);
    return words;
}

// The inclusive box of a validated DAG's solid voxels (max < min when it has none): each
// distinct node's box once, from its children's (a node's depth is unique once validated).
inline void dag_solid_box(std::span<const std::uint32_t> w, glm::ivec3& lo, glm::ivec3& hi) {
    struct box {
        glm::ivec3 lo{1 << 30}, hi{-1};
    };
    const int depth = int(w[VX_SV_HEADER_DEPTH]), leaf_depth = depth - VX_SV_LEAF_EDGE_BITS;
    std::unordered_map<std::uint32_t, box> known;
    auto box_of = [&](auto&& self, std::uint32_t at, int d) -> box {
        if (auto it = known.find(at); it != known.end()) return it->second;
        box b;
        if (d == leaf_depth) {
            std::uint64_t mask = w[at] | (std::uint64_t(w[at + 1]) << 32);
            for (int i = 0; i < 64; ++i)
                if (mask >> i & 1) {
                    glm::ivec3 p(i & 3, (i >> 2) & 3, i >> 4);
                    b.lo = glm::min(b.lo, p), b.hi = glm::max(b.hi, p);
                }
        } else {
            const int half = 1 << (depth - d - 1);
            int slot = 0;
            for (int o = 0; o < 8; ++o) {
                if (!(w[at] >> o & 1)) continue;
                box c = self(self, w[at + VX_SV_NODE_CHILDREN + slot++], d + 1);
                glm::ivec3 shift = glm::ivec3(o & 1, (o >> 1) & 1, o >> 2) * half;
                b.lo = glm::min(b.lo, c.lo + shift), b.hi = glm::max(b.hi, c.hi + shift);
            }
        }
        return known[at] = b;
    };
    box root = box_of(box_of, VX_SV_HEADER_WORDS, 0);
    lo = root.lo, hi = root.hi;
}

}  // namespace chunk_file_detail

// Creates the parent folders; the file appears under `path` only once it is complete.
inline void write_chunk_file(const std::filesystem::path& path, const chunk_record& c) {
    using namespace chunk_file_detail;
    namespace off = chunk_file_offset;
    std::string name = path.string();
    if (c.dag.size() < VX_SV_HEADER_WORDS || c.dag.size() >= max_blob_words)
        fail("chunk file ", name, ": cannot write a DAG of ", c.dag.size(), " words (expected [", VX_SV_HEADER_WORDS,
             ", ", max_blob_words, "))");
    unsigned char h[chunk_file_header_bytes] = {};
    put32(h, off::magic, chunk_file_magic);
    put32(h, off::version, chunk_file_version);
    put32(h, off::lod, std::uint32_t(c.key.lod));
    put32(h, off::chunk_bits, std::uint32_t(c.chunk_bits));
    for (int a = 0; a < 3; ++a) {
        put32(h, off::cell + 4 * a, std::uint32_t(c.key.cell[a]));
        put32(h, off::solid_min + 4 * a, std::uint32_t(c.solid_min[a]));
        put32(h, off::solid_max + 4 * a, std::uint32_t(c.solid_max[a]));
    }
    put32(h, off::source_hash, c.source_hash);
    put64(h, off::voxel_count, c.voxel_count);
    put64(h, off::dag_words, c.dag.size());
    put64(h, off::checksum, checksum(h, c.dag));

    std::error_code ec;
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
    if (ec) fail("chunk file ", name, ": cannot create its folder (", ec.message(), ")");
    std::filesystem::path tmp = path;
    tmp += ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out) fail("chunk file ", name, ": cannot open ", tmp.string(), " for writing");
        out.write(reinterpret_cast<const char*>(h), sizeof h);
        out.write(reinterpret_cast<const char*>(c.dag.data()), std::streamsize(c.dag.size() * 4));
        out.close();
        if (!out) {
            std::filesystem::remove(tmp, ec);
            fail("chunk file ", name, ": write to ", tmp.string(), " failed");
        }
    }
    // rename() replaces an existing file atomically on POSIX: a reader sees the old or the new one.
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        fail("chunk file ", name, ": cannot rename ", tmp.string(), " into place (", ec.message(), ")");
    }
}

// expected_chunk_bits: the world's chunk size, or -1 to accept any in [4, 10].
inline chunk_record read_chunk_file(const std::filesystem::path& path, int expected_chunk_bits = -1) {
    using namespace chunk_file_detail;
    namespace off = chunk_file_offset;
    std::string name = path.string();
    auto bad = [&](std::uint64_t offset, auto&&... what) { fail("chunk file ", name, ": offset ", offset, ": ", what...); };
    std::error_code ec;
    std::uint64_t size = std::filesystem::file_size(path, ec);
    if (ec) fail("chunk file ", name, ": cannot read (", ec.message(), ")");
    if (size < chunk_file_header_bytes)
        bad(0, "truncated, ", size, " bytes is shorter than the ", chunk_file_header_bytes, "-byte header");
    std::ifstream in(path, std::ios::binary);
    unsigned char h[chunk_file_header_bytes];
    if (!in.read(reinterpret_cast<char*>(h), sizeof h)) fail("chunk file ", name, ": cannot read the header");
    // Magic and version first: a file of another kind should say so, not complain about its size.
    if (get32(h, off::magic) != chunk_file_magic)
        bad(off::magic, "bad magic ", get32(h, off::magic), " (expected ", chunk_file_magic, ", \"VXCK\")");
    if (get32(h, off::version) != chunk_file_version)
        bad(off::version, "unsupported version ", get32(h, off::version), " (this build reads version ", chunk_file_version, ")");
    // The sizes before any allocation: the DAG's against what its voxel count can need,
    // the file's against the DAG's (a sparse file may claim gigabytes it does not hold).
    auto signed32 = [&](std::size_t at) { return std::int32_t(get32(h, at)); };
    chunk_record c;
    c.chunk_bits = signed32(off::chunk_bits);
    if (c.chunk_bits < chunk_min_bits || c.chunk_bits > chunk_max_bits)
        bad(off::chunk_bits, "chunk_bits ", c.chunk_bits, " is outside [", chunk_min_bits, ", ", chunk_max_bits, "]");
    if (expected_chunk_bits >= 0 && c.chunk_bits != expected_chunk_bits)
        bad(off::chunk_bits, "chunk_bits ", c.chunk_bits, " (expected ", expected_chunk_bits, ", the world's chunk size)");
    c.voxel_count = get64(h, off::voxel_count);
    const std::uint64_t cube = std::uint64_t(1) << (3 * c.chunk_bits);
    if (c.voxel_count > cube) bad(off::voxel_count, "voxel count ", c.voxel_count, " is more than the chunk's ", cube, " voxels");
    std::uint64_t words = get64(h, off::dag_words);
    std::uint64_t limit = std::min<std::uint64_t>(dag_word_limit(c.chunk_bits, c.voxel_count), max_blob_words - 1);
    if (words < VX_SV_HEADER_WORDS || words > limit)
        bad(off::dag_words, "DAG size of ", words, " words is outside [", VX_SV_HEADER_WORDS, ", ", limit,
            "], the most a DAG of ", c.voxel_count, " voxels in a chunk of 2^", c.chunk_bits, " a side can need");
    std::uint64_t expected_size = chunk_file_header_bytes + 4 * words;
    if (size != expected_size)
        bad(off::dag_words, "file is ", size, " bytes; a DAG of ", words, " words needs ", expected_size);
    c.dag.resize(words);
    if (!in.read(reinterpret_cast<char*>(c.dag.data()), std::streamsize(words * 4))) fail("chunk file ", name, ": read failed");
    std::uint64_t sum = checksum(h, c.dag);
    if (sum != get64(h, off::checksum))
        bad(off::checksum, "checksum ", get64(h, off::checksum), " does not match the content's ", sum);

    // Fields.
    c.key.lod = signed32(off::lod);
    if (c.key.lod < 0 || c.key.lod > chunk_max_lod) bad(off::lod, "lod ", c.key.lod, " is outside [0, ", chunk_max_lod, "]");
    const int edge = 1 << c.chunk_bits;
    bool empty = false;
    for (int a = 0; a < 3; ++a) {
        c.key.cell[a] = signed32(off::cell + 4 * a);
        c.solid_min[a] = signed32(off::solid_min + 4 * a);
        c.solid_max[a] = signed32(off::solid_max + 4 * a);
        empty |= c.solid_max[a] < c.solid_min[a];
    }
    c.source_hash = get32(h, off::source_hash);
    if (!empty)
        for (int a = 0; a < 3; ++a) {
            if (c.solid_min[a] < 0)
                bad(off::solid_min + 4 * a, "solid min ", c.solid_min[a], " is outside [0, ", edge, ")");
            if (c.solid_max[a] >= edge)
                bad(off::solid_max + 4 * a, "solid max ", c.solid_max[a], " is outside [0, ", edge, ")");
        }
    if (empty != (c.voxel_count == 0))
        bad(off::voxel_count, "voxel count ", c.voxel_count, " but the solid box is ", empty ? "empty" : "not empty");

    // The DAG: its header against the chunk's cube (the walk's depth comes from it), then
    // its structure.
    auto dag_bad = [&](std::uint64_t word, auto&&... what) {
        bad(chunk_file_header_bytes + 4 * word, "(DAG word ", word, ") ", what...);
    };
    auto expect = [&](std::uint64_t word, std::uint64_t want, const char* what) {
        if (c.dag[word] != want) dag_bad(word, what, " ", c.dag[word], " (expected ", want, ")");
    };
    expect(VX_SV_HEADER_DEPTH, std::uint64_t(c.chunk_bits), "DAG depth");
    for (int a = 0; a < 3; ++a) {
        expect(VX_SV_HEADER_ORIGIN + a, 0, "DAG origin");
        expect(VX_SV_HEADER_SHIFT + a, 0, "DAG shift");
        expect(VX_SV_HEADER_EXTENT + a, std::uint64_t(edge), "DAG extent");
    }
    svdag_detail::validate_blob(c.dag, dag_bad);
    std::uint64_t dag_voxels = c.dag[VX_SV_HEADER_VOXELS];  // the validator checked it against the nodes
    if (dag_voxels != c.voxel_count)
        bad(off::voxel_count, "voxel count ", c.voxel_count, " does not match the DAG's ", dag_voxels);
    // The solid box is where the walk looks: one smaller than the DAG's voxels hides some.
    if (!empty) {
        glm::ivec3 lo, hi;
        dag_solid_box(c.dag, lo, hi);
        for (int a = 0; a < 3; ++a) {
            if (c.solid_min[a] != lo[a])
                bad(off::solid_min + 4 * a, "solid min ", c.solid_min[a], " is not the DAG's voxels' ", lo[a]);
            if (c.solid_max[a] != hi[a])
                bad(off::solid_max + 4 * a, "solid max ", c.solid_max[a], " is not the DAG's voxels' ", hi[a]);
        }
    }
    return c;
}

}  // namespace voxray
