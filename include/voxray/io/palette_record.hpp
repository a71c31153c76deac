// A palette as bytes in a structure's file (brickmap files from version 2): 256 records
// of 28 bytes, one per palette index, everything little endian.
//
//   byte  0   1   2   3   4      5 .. 7     8          12         16    20         24
//        +---+---+---+---+------+----------+----------+----------+-----+----------+-------------+
//        | r | g | b | a | kind | 0  0  0  | roughness| metalness| ior | emission | transparency|
//        +---+---+---+---+------+----------+----------+----------+-----+----------+-------------+
//                                 reserved   f32 each (IEEE 754 binary32)
//
// Decoding checks the reserved bytes, the kind and every number's range
// (material_range_error), and names the byte offset of a bad field.
#pragma once
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/model/palette.hpp"

namespace voxray::io {

inline constexpr std::size_t palette_record_bytes = 28;
inline constexpr std::size_t palette_bytes = palette_record_bytes * palette::size;

inline std::vector<unsigned char> encode_palette(const palette& p) {
    std::vector<unsigned char> out(palette_bytes, 0);
    for (int i = 0; i < palette::size; ++i) {
        const palette_entry& e = p[std::uint8_t(i)];
        unsigned char* r = out.data() + std::size_t(i) * palette_record_bytes;
        r[0] = e.colour.r, r[1] = e.colour.g, r[2] = e.colour.b, r[3] = e.colour.a;
        r[4] = std::uint8_t(e.mat.kind);
        const float f[5] = {e.mat.roughness, e.mat.metalness, e.mat.ior, e.mat.emission, e.mat.transparency};
        std::memcpy(r + 8, f, sizeof f);
    }
    return out;
}

// `bytes` holds palette_bytes; `file` and `offset` (of the first byte) name errors.
inline palette decode_palette(const unsigned char* bytes, const std::string& file, std::uint64_t offset) {
    palette p;
    for (int i = 0; i < palette::size; ++i) {
        const unsigned char* r = bytes + std::size_t(i) * palette_record_bytes;
        std::uint64_t at = offset + std::uint64_t(i) * palette_record_bytes;
        if (r[5] || r[6] || r[7])
            fail(file, ": offset ", at + 5, ": palette entry ", i, ": reserved bytes ", int(r[5]), " ", int(r[6]), " ",
                 int(r[7]), " are not zero");
        palette_entry& e = p[std::uint8_t(i)];
        e.colour = {r[0], r[1], r[2], r[3]};
        if (r[4] > std::uint8_t(material_kind::cloud))
            fail(file, ": offset ", at + 4, ": palette entry ", i, ": material kind ", int(r[4]), " is unknown (0..",
                 int(material_kind::cloud), ")");
        e.mat.kind = material_kind(r[4]);
        float f[5];
        std::memcpy(f, r + 8, sizeof f);
        e.mat.roughness = f[0], e.mat.metalness = f[1], e.mat.ior = f[2], e.mat.emission = f[3];
        e.mat.transparency = f[4];
        if (std::string why = material_range_error(e.mat); !why.empty())
            fail(file, ": offset ", at + 8, ": palette entry ", i, ": ", why);
    }
    return p;
}

}  // namespace voxray::io
