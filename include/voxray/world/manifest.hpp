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
}  // namespace manifest_detail

inline void write_manifest(const std::filesystem::path& dir, const world_manifest& m) {
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
    std::filesystem::create_directories(dir);
    auto tmp = manifest_path(dir);
    tmp += ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(b.data()), std::streamsize(b.size()));
        if (!out) fail("world manifest ", tmp.string(), ": write failed");
    }
    std::filesystem::rename(tmp, manifest_path(dir));
}

inline world_manifest read_manifest(const std::filesystem::path& dir) {
    using manifest_detail::get;
    auto path = manifest_path(dir);
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
    std::uint64_t n = get<std::uint64_t>(head, 80);
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

    world_manifest m;
    m.grid.chunk_bits = get<std::int32_t>(b, 8);
    m.grid.top_lod = get<std::int32_t>(b, 12);
    for (int a = 0; a < 3; ++a) {
        m.grid.origin[a] = get<std::int32_t>(b, 16 + 4 * std::size_t(a));
        m.grid.cells[a] = get<std::int32_t>(b, 28 + 4 * std::size_t(a));
        m.bounds.min[a] = get<std::int32_t>(b, 40 + 4 * std::size_t(a));
        m.bounds.max[a] = get<std::int32_t>(b, 52 + 4 * std::size_t(a));
    }
    auto check = [&](bool ok, std::size_t offset, auto value, const char* expected) {
        if (!ok) fail("world manifest ", name, ": offset ", offset, ": ", value, " (expected ", expected, ")");
    };
    check(m.grid.chunk_bits >= VX_WD_MIN_CHUNK_BITS && m.grid.chunk_bits <= VX_WD_MAX_CHUNK_BITS, 8, m.grid.chunk_bits, "chunk_bits in [4, 10]");
    check(m.grid.top_lod >= 0 && m.grid.top_lod <= VX_WD_MAX_LOD, 12, m.grid.top_lod, "top_lod in [0, 20]");
    for (int a = 0; a < 3; ++a) check(m.grid.cells[a] >= 1 && m.grid.cells[a] <= (1 << 20), 28 + 4 * std::size_t(a), m.grid.cells[a], "cells in [1, 2^20]");
    std::uint32_t kind = get<std::uint32_t>(b, 64);
    check(kind <= 1u, 64, kind, "0 (exact) or 1 (colour blocks)");
    m.attributes = kind == 0u ? svdag_attributes::exact : svdag_attributes::colour_blocks;
    m.colour_error = get<float>(b, 68);
    m.density = get<std::int32_t>(b, 72);
    check(m.density >= 1 && m.density <= 8, 72, m.density, "density in [1, 8]");
    m.source_hash = get<std::uint32_t>(b, 76);
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
    }
    return m;
}

}  // namespace voxray
