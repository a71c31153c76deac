// MagicaVoxel's default palette, used when a file has no RGBA chunk.
//
// The 256 colours follow a simple rule, so the table is generated at compile time
// instead of being pasted as 256 literals (tests check entries against the spec):
//
//   index 0          unused (empty voxel), transparent black
//   index 1..215     the 6x6x6 cube of channel levels {ff, cc, 99, 66, 33, 00},
//                    blue changing fastest, then green, then red, starting at white
//                    (ff,ff,ff) and leaving out the cube's last entry, black
//   index 216..225   red ramp   (ee,00,00) (dd,00,00) ... (11,00,00)
//   index 226..235   green ramp (00,ee,00) ... (00,11,00)
//   index 236..245   blue ramp  (00,00,ee) ... (00,00,11)
//   index 246..255   grey ramp  (ee,ee,ee) ... (11,11,11)
//
// The ramps use the levels ee dd bb aa 88 77 55 44 22 11: the multiples of 0x11 that
// the cube does not already have.
//
// Unlike the RGBA chunk (whose entry i is palette index i + 1), this table is indexed
// directly by palette index.
#pragma once
#include <array>
#include <cstdint>

#include "voxray/model/palette.hpp"

namespace voxray::io {

inline constexpr std::array<rgba, 256> vox_default_palette = [] {
    std::array<rgba, 256> p{};
    p[0] = {0, 0, 0, 0};
    int i = 1;
    for (int r = 5; r >= 0; --r)
        for (int g = 5; g >= 0; --g)
            for (int b = 5; b >= 0; --b)
                if (i < 216) p[i++] = {std::uint8_t(r * 0x33), std::uint8_t(g * 0x33), std::uint8_t(b * 0x33), 255};
    constexpr std::uint8_t ramp[10] = {0xee, 0xdd, 0xbb, 0xaa, 0x88, 0x77, 0x55, 0x44, 0x22, 0x11};
    for (int channel = 0; channel < 4; ++channel)
        for (std::uint8_t v : ramp) {
            rgba c{0, 0, 0, 255};
            if (channel == 0 || channel == 3) c.r = v;
            if (channel == 1 || channel == 3) c.g = v;
            if (channel == 2 || channel == 3) c.b = v;
            p[i++] = c;
        }
    return p;
}();

}  // namespace voxray::io
