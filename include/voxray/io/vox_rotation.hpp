// The rotation of a MagicaVoxel transform node: a signed permutation matrix packed in
// one byte (the `_r` key of an nTRN frame). Each row of the 3x3 matrix has exactly one
// non-zero entry, +1 or -1:
//
//    bit  7   6   5   4   3   2   1   0
//       +---+---+---+---+-------+-------+
//       | 0 |s2 |s1 |s0 |  c1   |  c0   |
//       +---+---+---+---+-------+-------+
//   c0: column of the non-zero entry in row 0      (0..2)
//   c1: column of the non-zero entry in row 1      (0..2, != c0)
//   c2: the remaining column, 3 - c0 - c1 (implicit)
//   sN: sign of row N's entry, 1 = negative
//
// The matrix is row-major and acts on column vectors: out[i] = s_i * in[c_i]. Example:
// _r = 38 = 0b0100110 -> c0 = 2, c1 = 1, s1 = 1:
//     | 0  0  1 |
//     | 0 -1  0 |
//     | 1  0  0 |
#pragma once
#include <array>
#include <cstdint>
#include <optional>

#include <glm/vec3.hpp>

namespace voxray::io {

struct vox_rotation {
    std::array<std::uint8_t, 3> column{0, 1, 2};  // column of row i's non-zero entry
    std::array<std::int8_t, 3> sign{1, 1, 1};      // its value, +1 or -1

    static vox_rotation identity() { return {}; }

    // Decodes the packed byte; nullopt when the two column indices are out of range or
    // equal, or bit 7 is set (no rotation MagicaVoxel writes has those).
    static std::optional<vox_rotation> from_byte(int packed) {
        if (packed < 0 || packed > 0x7f) return std::nullopt;
        int c0 = packed & 3, c1 = (packed >> 2) & 3;
        if (c0 > 2 || c1 > 2 || c0 == c1) return std::nullopt;
        vox_rotation r;
        r.column = {std::uint8_t(c0), std::uint8_t(c1), std::uint8_t(3 - c0 - c1)};
        for (int i = 0; i < 3; ++i) r.sign[i] = (packed >> (4 + i)) & 1 ? -1 : 1;
        return r;
    }

    // Matrix entry (row, col), for tests and debugging.
    int at(int row, int col) const { return column[row] == col ? sign[row] : 0; }

    // this * v, in 64-bit so composed translations cannot overflow.
    template <class V>
    V apply(const V& v) const {
        V out;
        for (int i = 0; i < 3; ++i) out[i] = sign[i] * v[column[i]];
        return out;
    }

    // The product this * rhs (apply rhs first, then this).
    vox_rotation operator*(const vox_rotation& rhs) const {
        vox_rotation out;
        for (int i = 0; i < 3; ++i) {
            out.column[i] = rhs.column[column[i]];
            out.sign[i] = std::int8_t(sign[i] * rhs.sign[column[i]]);
        }
        return out;
    }
    bool operator==(const vox_rotation&) const = default;
};

}  // namespace voxray::io
