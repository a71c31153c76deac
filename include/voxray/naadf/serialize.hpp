// NAADF files (.vxna): a 32-byte header, the blob words exactly as in memory (spare
// capacity included, so a load gives a bit-identical blob), then the palette. Little
// endian.
//
//   offset  size  field
//        0     4  magic "VXNA" (0x414e5856)
//        4     4  file version (1)
//        8     8  blob words                    file size must be 32 + 4 * words + 7168
//       16     8  solid voxel count             checked against the content
//       24     8  checksum: FNV-1a 64 over bytes 0..23, every blob word, the palette
//       32        blob words (naadf/layout.h)
//   32 + 4w 7168  palette: 256 records of 28 bytes (io/palette_record.hpp)
//
// A load trusts nothing: sizes before anything is allocated, the checksum before the
// content is parsed, then the content itself (naadf/restore.hpp). Every failure is a
// voxray::error naming the file, the byte offset and the value.
#pragma once
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "voxray/core/checksum.hpp"
#include "voxray/io/palette_record.hpp"
#include "voxray/naadf/naadf.hpp"
#include "voxray/naadf/restore.hpp"

namespace voxray {

static_assert(std::endian::native == std::endian::little, "NAADF files assume a little-endian host");

inline constexpr std::uint32_t naadf_file_magic = 0x414e5856u;  // "VXNA"
inline constexpr std::uint32_t naadf_file_version = 1;
inline constexpr std::size_t naadf_file_header_bytes = 32;

struct naadf_io {
    // Safe while other threads edit: the blob is copied under the lock, then written.
    static void save(const naadf& s, const std::filesystem::path& path) {
        auto frame = s.snapshot();
        blob_words words(frame.blob.begin(), frame.blob.end());
        std::vector<unsigned char> pal = io::encode_palette(s.palette_);
        frame.lock.unlock();
        unsigned char h[naadf_file_header_bytes] = {};
        auto put32 = [&](std::size_t at, std::uint32_t v) { std::memcpy(h + at, &v, 4); };
        auto put64 = [&](std::size_t at, std::uint64_t v) { std::memcpy(h + at, &v, 8); };
        put32(0, naadf_file_magic);
        put32(4, naadf_file_version);
        put64(8, words.size());
        put64(16, frame.voxels);
        fnv64 sum;
        sum.bytes(h, 24);
        sum.words(words.data(), words.size());
        sum.bytes(pal.data(), pal.size());
        put64(24, sum.h);
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        if (!out) fail("naadf file ", path.string(), ": cannot open for writing");
        out.write(reinterpret_cast<const char*>(h), sizeof h);
        out.write(reinterpret_cast<const char*>(words.data()), std::streamsize(words.size() * 4));
        out.write(reinterpret_cast<const char*>(pal.data()), std::streamsize(pal.size()));
        if (!out) fail("naadf file ", path.string(), ": write failed");
    }

    static naadf load(const std::filesystem::path& path) {
        std::string name = path.string();
        std::error_code ec;
        std::uint64_t size = std::filesystem::file_size(path, ec);
        if (ec) fail("naadf file ", name, ": cannot read (", ec.message(), ")");
        if (size < naadf_file_header_bytes)
            fail("naadf file ", name, ": offset 0: truncated, ", size, " bytes is shorter than the ", naadf_file_header_bytes,
                 "-byte header");
        std::ifstream in(path, std::ios::binary);
        unsigned char h[naadf_file_header_bytes];
        if (!in.read(reinterpret_cast<char*>(h), sizeof h)) fail("naadf file ", name, ": cannot read the header");
        auto get32 = [&](std::size_t at) { std::uint32_t v; std::memcpy(&v, h + at, 4); return v; };
        auto get64 = [&](std::size_t at) { std::uint64_t v; std::memcpy(&v, h + at, 8); return v; };
        auto bad = [&](std::uint64_t offset, auto... what) { fail("naadf file ", name, ": offset ", offset, ": ", what...); };
        if (get32(0) != naadf_file_magic) bad(0, "bad magic ", get32(0), " (expected ", naadf_file_magic, ")");
        if (get32(4) != naadf_file_version)
            bad(4, "unsupported version ", get32(4), " (this build reads version ", naadf_file_version, ")");
        std::uint64_t words = get64(8);
        if (words < VX_NA_HEADER_WORDS || words >= max_blob_words)
            bad(8, "blob size of ", words, " words is outside [", VX_NA_HEADER_WORDS, ", ", max_blob_words, ")");
        std::uint64_t expected = naadf_file_header_bytes + 4 * words + io::palette_bytes;
        if (size != expected) bad(8, "file is ", size, " bytes; a blob of ", words, " words needs ", expected);
        blob_words blob(words);
        std::vector<unsigned char> pal(io::palette_bytes);
        if (!in.read(reinterpret_cast<char*>(blob.data()), std::streamsize(words * 4)) ||
            !in.read(reinterpret_cast<char*>(pal.data()), std::streamsize(pal.size())))
            fail("naadf file ", name, ": read failed");
        fnv64 sum;
        sum.bytes(h, 24);
        sum.words(blob.data(), blob.size());
        sum.bytes(pal.data(), pal.size());
        if (sum.h != get64(24)) bad(24, "checksum ", get64(24), " does not match the content's ", sum.h);
        auto r = naadf_detail::restore_blob(blob, [&](std::uint64_t word, auto... what) {
            bad(naadf_file_header_bytes + 4 * word, "(blob word ", word, ") ", what...);
        });
        if (r.voxels != get64(16)) bad(16, "voxel count ", get64(16), " does not match the content's ", r.voxels);
        voxray::palette palette = io::decode_palette(pal.data(), "naadf file " + name, naadf_file_header_bytes + 4 * words);
        naadf_detail::cell_store store;
        store.adopt(std::move(blob), 0.0);
        store.set_in_use(r.chunk_live, r.block_live);
        return naadf(std::move(store), std::move(r.groups), r.bounds, r.voxels, std::move(palette));
    }
};

inline void save(const naadf& s, const std::filesystem::path& path) { naadf_io::save(s, path); }
inline naadf load_naadf(const std::filesystem::path& path) { return naadf_io::load(path); }

}  // namespace voxray
