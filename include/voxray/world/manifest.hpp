// A world on disk: a folder of chunk files (world/chunk_file.hpp) and its manifest,
// world.vxwm, which says how the world is cut (its grid and LODs), how it was built, and
// which chunks exist, so that LOD selection and the residency budget need no file access.
// The builder writes the manifest last: a folder without one is a build not finished.
// Little endian.
//
//   offset  size  field
//        0     4  magic "VXWM" (0x4d575856)
//        4     4  file version (1)
//        8     4  chunk_bits                    [4, 10]
//       12     4  top_lod                       [0, 20]
//       16    12  grid origin x, y, z (signed)
//       28    12  cells x, y, z                 each in [1, 2^20]
//       40    24  bounds min x, y, z, max x, y, z (signed; max exclusive)
//       64     4  attributes                    0 exact, 1 colour blocks
//       68     4  colour error (float)
//       72     4  density                       [1, 8]
//       76     4  source hash                   of the input and the build options
//       80     8  chunk count N
//       88     8  checksum: FNV-1a 64 over bytes 0..87 and the chunk table
//       96  32 N  chunks, sorted by (lod, z, y, x): lod, cell x, y, z (signed),
//                 solid voxels (8 bytes), file bytes (8 bytes)
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "voxray/core/box.hpp"
#include "voxray/core/checksum.hpp"
#include "voxray/core/error.hpp"
#include "voxray/svdag/builder.hpp"
#include "voxray/world/chunk.hpp"
#include "voxray/world/chunk_file.hpp"
#include "voxray/world/world_blob.hpp"

namespace voxray {

inline constexpr std::uint32_t manifest_magic = 0x4d575856u;  // "VXWM"
inline constexpr std::uint32_t manifest_version = 1;
inline constexpr std::size_t manifest_header_bytes = 96, manifest_chunk_bytes = 32;

struct manifest_chunk {
    chunk_key key;
    std::uint64_t voxel_count = 0;
    std::uint64_t file_bytes = 0;
};

struct world_manifest {
    world_grid grid;
    box3i bounds;
    svdag_attributes attributes = svdag_attributes::exact;
    float colour_error = 0.05f;
    int density = 2;
    std::uint32_t source_hash = 0;
    std::vector<manifest_chunk> chunks;  // the non-empty ones, sorted by (lod, z, y, x)

    void sort() {
        std::sort(chunks.begin(), chunks.end(), [](auto& a, auto& b) { return chunk_key_less{}(a.key, b.key); });
    }
    // The chunk of that key, or nullptr when that region has no voxels at that LOD.
    const manifest_chunk* find(const chunk_key& k) const {
        auto it = std::lower_bound(chunks.begin(), chunks.end(), k,
                                   [](const manifest_chunk& c, const chunk_key& key) { return chunk_key_less{}(c.key, key); });
        return it != chunks.end() && it->key == k ? &*it : nullptr;
    }
    std::uint64_t disk_bytes(int lod = -1) const {
        std::uint64_t n = 0;
        for (auto& c : chunks)
            if (lod < 0 || c.key.lod == lod) n += c.file_bytes;
        return n;
    }
};

inline std::filesystem::path manifest_path(const std::filesystem::path& dir) { return dir / "world.vxwm"; }

namespace manifest_detail {
template <class T>
void put(std::vector<unsigned char>& b, std::size_t at, T v) {
    std::memcpy(b.data() + at, &v, sizeof v);
}
template <class T>
T get(const std::vector<unsigned char>& b, std::size_t at) {
    T v;
    std::memcpy(&v, b.data() + at, sizeof v);
    return v;
}

// Cells of every LOD of the grid: no world has more chunks.
inline std::uint64_t chunk_cells(const world_grid& g) {
    std::uint64_t n = 0;
    for (int lod = 0; lod <= g.top_lod; ++lod) {
        std::uint64_t level = 1;
        for (int a = 0; a < 3; ++a) level *= (std::uint64_t(g.cells[a]) + (std::uint64_t(1) << lod) - 1) >> lod;
        n += level;
    }
    return n;
}

// The grid as world_grid::fit makes it, which the walk's arithmetic relies on: an origin
// on the top LOD's chunk grid, every voxel's coordinate within 32 bits, at most 2 chunks
// a side at the top LOD, and bounds inside the grid (or an empty world).
template <class Check>
void check_grid(const world_manifest& m, Check&& check) {
    const world_grid& g = m.grid;
    const std::int64_t region = std::int64_t(1) << (g.chunk_bits + g.top_lod), edge = std::int64_t(1) << g.chunk_bits;
    for (int a = 0; a < 3; ++a) {
        std::size_t at = 16 + 4 * std::size_t(a);
        std::int64_t lo = g.origin[a], hi = lo + edge * g.cells[a];
        check(lo % region == 0, at, lo, "an origin on the top LOD's chunk grid");
        check(hi <= INT32_MAX, at, lo, "a grid whose far corner fits 32 bits");
        check(((std::int64_t(g.cells[a]) + (std::int64_t(1) << g.top_lod) - 1) >> g.top_lod) <= 2, 28 + 4 * std::size_t(a),
              g.cells[a], "at most 2 chunks a side at the top LOD");
        if (m.bounds.empty()) continue;
        check(m.bounds.min[a] >= lo && m.bounds.min[a] < hi, 40 + 4 * std::size_t(a), m.bounds.min[a], "bounds inside the grid");
        check(m.bounds.max[a] > lo && m.bounds.max[a] <= hi, 52 + 4 * std::size_t(a), m.bounds.max[a], "bounds inside the grid");
    }
}

}  // namespace manifest_detail

// A manifest under any name: a sharded build's shards list their chunks in one each
// (world/build/shard.hpp). `path` is the file; its folder is created.
inline void write_manifest_file(const std::filesystem::path& path, const world_manifest& m) {
    using manifest_detail::put;
    std::vector<unsigned char> b(manifest_header_bytes + manifest_chunk_bytes * m.chunks.size(), 0);
    put<std::uint32_t>(b, 0, manifest_magic);
    put<std::uint32_t>(b, 4, manifest_version);
    put<std::int32_t>(b, 8, m.grid.chunk_bits);
    put<std::int32_t>(b, 12, m.grid.top_lod);
    for (int a = 0; a < 3; ++a) {
        put<std::int32_t>(b, 16 + 4 * std::size_t(a), m.grid.origin[a]);
        put<std::int32_t>(b, 28 + 4 * std::size_t(a), m.grid.cells[a]);
        put<std::int32_t>(b, 40 + 4 * std::size_t(a), m.bounds.min[a]);
        put<std::int32_t>(b, 52 + 4 * std::size_t(a), m.bounds.max[a]);
    }
    put<std::uint32_t>(b, 64, m.attributes == svdag_attributes::exact ? 0u : 1u);
    put<float>(b, 68, m.colour_error);
    put<std::int32_t>(b, 72, m.density);
    put<std::uint32_t>(b, 76, m.source_hash);
    put<std::uint64_t>(b, 80, m.chunks.size());
    for (std::size_t i = 0; i < m.chunks.size(); ++i) {
        std::size_t at = manifest_header_bytes + manifest_chunk_bytes * i;
        put<std::int32_t>(b, at, m.chunks[i].key.lod);
        for (int a = 0; a < 3; ++a) put<std::int32_t>(b, at + 4 + 4 * std::size_t(a), m.chunks[i].key.cell[a]);
        put<std::uint64_t>(b, at + 16, m.chunks[i].voxel_count);
        put<std::uint64_t>(b, at + 24, m.chunks[i].file_bytes);
    }
    fnv64 sum;
    sum.bytes(b.data(), 88);
    sum.bytes(b.data() + manifest_header_bytes, b.size() - manifest_header_bytes);
    put<std::uint64_t>(b, 88, sum.h);
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    auto tmp = path;
    tmp += ".tmp";
    std::error_code ec;
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
        out.close();  // a full disk shows here, when the buffer is flushed
        if (!out) {
            std::filesystem::remove(tmp, ec);
            fail("world manifest ", tmp.string(), ": write failed (", b.size(), " bytes; is the disk full?)");
        }
    }
    std::filesystem::rename(tmp, path, ec);
    if (ec) fail("world manifest ", path.string(), ": cannot rename ", tmp.string(), " into place (", ec.message(), ")");
}

inline void write_manifest(const std::filesystem::path& dir, const world_manifest& m) {
    write_manifest_file(manifest_path(dir), m);
}

inline world_manifest read_manifest_file(const std::filesystem::path& path) {
    using manifest_detail::get;
    std::string name = path.string();
    std::error_code ec;
    auto size = std::filesystem::file_size(path, ec);
    if (ec) fail("world manifest ", name, ": cannot read it (", ec.message(), "); is this a finished world build?");
    if (size < manifest_header_bytes) fail("world manifest ", name, ": ", size, " bytes, shorter than its ", manifest_header_bytes, "-byte header");
    std::vector<unsigned char> head(manifest_header_bytes);
    std::ifstream in(path, std::ios::binary);
    in.read(reinterpret_cast<char*>(head.data()), std::streamsize(head.size()));
    if (get<std::uint32_t>(head, 0) != manifest_magic)
        fail("world manifest ", name, ": offset 0: magic ", get<std::uint32_t>(head, 0), " is not VXWM");
    if (get<std::uint32_t>(head, 4) != manifest_version)
        fail("world manifest ", name, ": offset 4: version ", get<std::uint32_t>(head, 4), ", this reader knows ", manifest_version);
    // The header's fields first (they bound the chunk count), then the size, before the
    // table is allocated: a sparse file may claim gigabytes it does not hold.
    world_manifest m;
    m.grid.chunk_bits = get<std::int32_t>(head, 8);
    m.grid.top_lod = get<std::int32_t>(head, 12);
    for (int a = 0; a < 3; ++a) {
        m.grid.origin[a] = get<std::int32_t>(head, 16 + 4 * std::size_t(a));
        m.grid.cells[a] = get<std::int32_t>(head, 28 + 4 * std::size_t(a));
        m.bounds.min[a] = get<std::int32_t>(head, 40 + 4 * std::size_t(a));
        m.bounds.max[a] = get<std::int32_t>(head, 52 + 4 * std::size_t(a));
    }
    auto check = [&](bool ok, std::size_t offset, auto value, const char* expected) {
        if (!ok) fail("world manifest ", name, ": offset ", offset, ": ", value, " (expected ", expected, ")");
    };
    check(m.grid.chunk_bits >= VX_WD_MIN_CHUNK_BITS && m.grid.chunk_bits <= VX_WD_MAX_CHUNK_BITS, 8, m.grid.chunk_bits, "chunk_bits in [4, 10]");
    check(m.grid.top_lod >= 0 && m.grid.top_lod <= VX_WD_MAX_LOD, 12, m.grid.top_lod, "top_lod in [0, 20]");
    for (int a = 0; a < 3; ++a) check(m.grid.cells[a] >= 1 && m.grid.cells[a] <= (1 << 20), 28 + 4 * std::size_t(a), m.grid.cells[a], "cells in [1, 2^20]");
    manifest_detail::check_grid(m, check);
    std::uint32_t kind = get<std::uint32_t>(head, 64);
    check(kind <= 1u, 64, kind, "0 (exact) or 1 (colour blocks)");
    m.attributes = kind == 0u ? svdag_attributes::exact : svdag_attributes::colour_blocks;
    m.colour_error = get<float>(head, 68);
    m.density = get<std::int32_t>(head, 72);
    check(m.density >= 1 && m.density <= 8, 72, m.density, "density in [1, 8]");
    m.source_hash = get<std::uint32_t>(head, 76);
    std::uint64_t n = get<std::uint64_t>(head, 80), cells = manifest_detail::chunk_cells(m.grid);
    check(n <= cells, 80, n, "at most one chunk per cell of every LOD");
    if (n > (size - manifest_header_bytes) / manifest_chunk_bytes || size != manifest_header_bytes + manifest_chunk_bytes * n)
        fail("world manifest ", name, ": offset 80: ", n, " chunks do not match the file size ", size);
    std::vector<unsigned char> b(std::size_t(size), 0);
    std::copy(head.begin(), head.end(), b.begin());
    in.read(reinterpret_cast<char*>(b.data() + manifest_header_bytes), std::streamsize(size - manifest_header_bytes));
    if (!in) fail("world manifest ", name, ": read failed");
    fnv64 sum;
    sum.bytes(b.data(), 88);
    sum.bytes(b.data() + manifest_header_bytes, b.size() - manifest_header_bytes);
    if (sum.h != get<std::uint64_t>(b, 88)) fail("world manifest ", name, ": offset 88: checksum mismatch (the file is corrupt)");

    const std::uint64_t cube = std::uint64_t(1) << (3 * m.grid.chunk_bits);
    m.chunks.resize(std::size_t(n));
    for (std::size_t i = 0; i < n; ++i) {
        std::size_t at = manifest_header_bytes + manifest_chunk_bytes * i;
        manifest_chunk& c = m.chunks[i];
        c.key.lod = get<std::int32_t>(b, at);
        for (int a = 0; a < 3; ++a) c.key.cell[a] = get<std::int32_t>(b, at + 4 + 4 * std::size_t(a));
        c.voxel_count = get<std::uint64_t>(b, at + 16);
        c.file_bytes = get<std::uint64_t>(b, at + 24);
        check(c.key.lod >= 0 && c.key.lod <= m.grid.top_lod, at, c.key.lod, "a LOD of the world");
        glm::ivec3 limit = (m.grid.cells + (1 << c.key.lod) - 1) >> c.key.lod;
        for (int a = 0; a < 3; ++a)
            check(c.key.cell[a] >= 0 && c.key.cell[a] < limit[a], at + 4 + 4 * std::size_t(a), c.key.cell[a], "a cell inside the grid");
        check(i == 0 || chunk_key_less{}(m.chunks[i - 1].key, c.key), at, i, "chunks sorted and unique");
        check(c.voxel_count >= 1 && c.voxel_count <= cube, at + 16, c.voxel_count, "solid voxels in [1, chunk volume]");
        check(c.file_bytes >= chunk_file_header_bytes + 4 * VX_SV_HEADER_WORDS && c.file_bytes % 4 == 0 &&
                  c.file_bytes <= chunk_file_header_bytes + 4 * chunk_file_detail::dag_word_limit(m.grid.chunk_bits, c.voxel_count),
              at + 24, c.file_bytes, "the size of a chunk file of that many voxels");
    }
    return m;
}

inline world_manifest read_manifest(const std::filesystem::path& dir) { return read_manifest_file(manifest_path(dir)); }

// A chunk the manifest lists, read from its folder and checked against the manifest: its
// size before anything is read (the manifest's file_bytes), then after the reader's own
// checks its key, build (source hash), voxel count and attribute kind, so that a chunk
// file of another build or another world is an error naming it, never shown.
inline chunk_record read_listed_chunk(const std::filesystem::path& dir, const world_manifest& m, const chunk_key& k) {
    auto path = chunk_file_path(dir, k);
    std::string name = path.string();
    const manifest_chunk* listed = m.find(k);
    if (!listed) fail("chunk file ", name, ": the world's manifest lists no such chunk");
    std::error_code ec;
    std::uint64_t size = std::filesystem::file_size(path, ec);
    if (ec) fail("chunk file ", name, ": cannot read (", ec.message(), ")");
    if (size != listed->file_bytes)
        fail("chunk file ", name, ": ", size, " bytes, but the manifest lists ", listed->file_bytes, " (a file of another build?)");
    chunk_record c = read_chunk_file(path, m.grid.chunk_bits);
    auto differs = [&](std::size_t offset, const char* what, auto has, auto listed_value) {
        fail("chunk file ", name, ": offset ", offset, ": ", what, " ", has, ", but the manifest's is ", listed_value,
             " (a file of another build?)");
    };
    if (!(c.key == k))
        fail("chunk file ", name, ": holds chunk (LOD ", c.key.lod, ", ", c.key.cell.x, " ", c.key.cell.y, " ", c.key.cell.z,
             "), not the one its name says");
    if (c.source_hash != m.source_hash) differs(chunk_file_offset::source_hash, "source hash", c.source_hash, m.source_hash);
    if (c.voxel_count != listed->voxel_count) differs(chunk_file_offset::voxel_count, "voxel count", c.voxel_count, listed->voxel_count);
    std::uint32_t kind = m.attributes == svdag_attributes::exact ? VX_SV_ATTRIBUTES_EXACT : VX_SV_ATTRIBUTES_COLOUR_BLOCKS;
    if (c.dag[VX_SV_HEADER_ATTRIBUTE_KIND] != kind)
        differs(chunk_file_header_bytes + 4 * VX_SV_HEADER_ATTRIBUTE_KIND, "attribute kind", c.dag[VX_SV_HEADER_ATTRIBUTE_KIND], kind);
    return c;
}

}  // namespace voxray
