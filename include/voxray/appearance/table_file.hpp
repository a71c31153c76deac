// Appearance table files (.vxap): a 48-byte header, then the rows' voxels, the records, the
// face pool and the precomputed shadows, little endian. A precompute takes minutes at
// 256^3; the file keeps it.
//
//   offset  size  field
//        0     4  magic "VXAP" (0x50415856)
//        4     4  file version: 2 with shadows, 1 without (which older builds read too)
//        8     4  record kind (0 averages, 1 compact, 2 six, 3 sggx, 4 faithful: table.hpp)
//       12     4  record words (layout.h: must be the kind's)
//       16     8  rows                           file size must be
//       24     8  face pool words                48 + 12 rows + 4 (rows x record words + face words)
//       32     8  checksum: FNV-1a 64 over          + (shadows ? 12 + rows : 0)
//                 bytes 0..31 and everything after byte 47
//       40     4  shadows: 1 if the table has them, else 0 (always 0 in version 1)
//       44     4  zero (reserved)
//       48        voxels: rows x (x, y, z) as int32, in the ordinal order (table.hpp)
//                 records: rows x record words
//                 face pool
//                 shadows: the light's direction (3 float32), then a visibility byte a row
//
// A load trusts nothing: sizes before anything is allocated, the checksum before the
// content is read, then the content (table_check.hpp: order, face ranges), so a walk never
// reads outside its buffers. Every failure is a voxray::error naming the file, the byte
// offset and the value.
#pragma once
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "voxray/appearance/table.hpp"
#include "voxray/appearance/table_check.hpp"
#include "voxray/core/checksum.hpp"
#include "voxray/core/error.hpp"

namespace voxray::appearance {

static_assert(std::endian::native == std::endian::little, "appearance table files assume a little-endian host");

inline constexpr std::uint32_t table_file_magic = 0x50415856u;  // "VXAP"
inline constexpr std::uint32_t table_file_version = 2;  // the newest this build reads and writes
inline constexpr std::size_t table_file_header_bytes = 48;
// Rows and face words a file may declare: far above any real table (2^28 rows is 512^3
// full), low enough that the sizes cannot overflow.
inline constexpr std::uint64_t table_file_max_rows = 1ull << 32;
inline constexpr std::uint64_t table_file_max_face_words = 1ull << 34;

namespace table_file_detail {

inline std::uint64_t shadow_bytes(bool shadows, std::uint64_t rows) { return shadows ? 12 + rows : 0; }

inline std::vector<unsigned char> body(const appearance_table& t) {
    std::vector<unsigned char> b(t.voxels.size() * 12 + 4 * (t.words.size() + t.faces.size()) +
                                 shadow_bytes(bool(t.shadows), t.voxels.size()));
    unsigned char* at = b.data();
    for (glm::ivec3 v : t.voxels) {
        std::int32_t xyz[3] = {v.x, v.y, v.z};
        std::memcpy(at, xyz, 12);
        at += 12;
    }
    if (!t.words.empty()) std::memcpy(at, t.words.data(), 4 * t.words.size());
    at += 4 * t.words.size();
    if (!t.faces.empty()) std::memcpy(at, t.faces.data(), 4 * t.faces.size());
    at += 4 * t.faces.size();
    if (t.shadows) {
        float l[3] = {t.shadows->to_light.x, t.shadows->to_light.y, t.shadows->to_light.z};
        std::memcpy(at, l, 12);
        if (!t.shadows->visibility.empty()) std::memcpy(at + 12, t.shadows->visibility.data(), t.voxels.size());
    }
    return b;
}

inline std::uint64_t checksum(const unsigned char* header, const std::vector<unsigned char>& body) {
    fnv64 sum;
    sum.bytes(header, 32);
    sum.bytes(body.data(), body.size());
    return sum.h;
}

}  // namespace table_file_detail

inline void save_table(const appearance_table& t, const std::filesystem::path& path) {
    check_table(t, ("appearance table file " + path.string()).c_str());
    std::vector<unsigned char> body = table_file_detail::body(t);
    unsigned char h[table_file_header_bytes] = {};
    auto put32 = [&](std::size_t at, std::uint32_t v) { std::memcpy(h + at, &v, 4); };
    auto put64 = [&](std::size_t at, std::uint64_t v) { std::memcpy(h + at, &v, 8); };
    put32(0, table_file_magic);
    put32(4, t.shadows ? 2 : 1);
    put32(8, std::uint32_t(t.kind));
    put32(12, std::uint32_t(t.record_words));
    put64(16, t.voxels.size());
    put64(24, t.faces.size());
    put64(32, table_file_detail::checksum(h, body));
    put32(40, t.shadows ? 1 : 0);
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    if (!out) fail("appearance table file ", path.string(), ": cannot open for writing");
    out.write(reinterpret_cast<const char*>(h), sizeof h);
    out.write(reinterpret_cast<const char*>(body.data()), std::streamsize(body.size()));
    if (!out) fail("appearance table file ", path.string(), ": write failed");
}

inline appearance_table load_table(const std::filesystem::path& path) {
    std::string name = path.string();
    std::error_code ec;
    std::uint64_t size = std::filesystem::file_size(path, ec);
    if (ec) fail("appearance table file ", name, ": cannot read (", ec.message(), ")");
    auto bad = [&](std::uint64_t offset, auto... what) {
        fail("appearance table file ", name, ": offset ", offset, ": ", what...);
    };
    if (size < table_file_header_bytes)
        bad(0, "truncated: ", size, " bytes is shorter than the ", table_file_header_bytes, "-byte header");
    std::ifstream in(path, std::ios::binary);
    unsigned char h[table_file_header_bytes];
    if (!in.read(reinterpret_cast<char*>(h), sizeof h))
        fail("appearance table file ", name, ": cannot read the header");
    auto get32 = [&](std::size_t at) { std::uint32_t v; std::memcpy(&v, h + at, 4); return v; };
    auto get64 = [&](std::size_t at) { std::uint64_t v; std::memcpy(&v, h + at, 8); return v; };
    if (get32(0) != table_file_magic) bad(0, "bad magic ", get32(0), " (expected ", table_file_magic, ")");
    const std::uint32_t version = get32(4);
    if (version != 1 && version != 2)
        bad(4, "unsupported version ", version, " (this build reads versions 1 to ", table_file_version, ")");
    if (get32(44) != 0) bad(44, "reserved word is ", get32(44), ", not 0");
    if (get32(40) > (version == 2 ? 1u : 0u))
        bad(40, "shadows flag is ", get32(40), " (", version == 2 ? "0 or 1" : "0 in version 1", ")");
    const bool shadows = get32(40) == 1;
    appearance_table t;
    t.kind = record_kind(get32(8));
    int words = record_words(t.kind);
    if (words == 0) bad(8, "unknown record kind ", get32(8));
    if (get32(12) != std::uint32_t(words))
        bad(12, record_name(t.kind), " records take ", words, " words, the file says ", get32(12));
    t.record_words = words;
    std::uint64_t rows = get64(16), face_words = get64(24);
    if (rows > table_file_max_rows) bad(16, rows, " rows, above the limit of ", table_file_max_rows);
    if (face_words > table_file_max_face_words)
        bad(24, face_words, " face words, above the limit of ", table_file_max_face_words);
    std::uint64_t expected = table_file_header_bytes + 12 * rows + 4 * (rows * words + face_words) +
                             table_file_detail::shadow_bytes(shadows, rows);
    if (size != expected)
        bad(16, "file is ", size, " bytes; ", rows, " rows and ", face_words, " face words",
            shadows ? " and shadows" : "", " need ", expected);
    std::vector<unsigned char> body(size - table_file_header_bytes);
    if (!in.read(reinterpret_cast<char*>(body.data()), std::streamsize(body.size())))
        fail("appearance table file ", name, ": read failed");
    std::uint64_t sum = table_file_detail::checksum(h, body);
    if (sum != get64(32)) bad(32, "checksum ", get64(32), " does not match the content's ", sum);
    t.voxels.resize(rows);
    const unsigned char* at = body.data();
    for (glm::ivec3& v : t.voxels) {
        std::int32_t xyz[3];
        std::memcpy(xyz, at, 12);
        v = {xyz[0], xyz[1], xyz[2]};
        at += 12;
    }
    t.words.resize(rows * words);
    if (!t.words.empty()) std::memcpy(t.words.data(), at, 4 * t.words.size());
    at += 4 * t.words.size();
    t.faces.resize(face_words);
    if (!t.faces.empty()) std::memcpy(t.faces.data(), at, 4 * t.faces.size());
    at += 4 * t.faces.size();
    if (shadows) {
        float l[3];
        std::memcpy(l, at, 12);
        t.shadows = table_shadows{{l[0], l[1], l[2]}, std::vector<std::uint8_t>(at + 12, at + 12 + rows)};
    }
    std::uint64_t records_at = table_file_header_bytes + 12 * rows;
    check_table(t, [&](std::size_t row, auto... what) {
        bad(records_at + 4 * row * words, "(row ", row, ") ", what...);
    });
    return t;
}

}  // namespace voxray::appearance
