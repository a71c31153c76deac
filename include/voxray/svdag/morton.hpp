// Morton (Z-order) codes of 3D cell coordinates, x in the lowest bit of each triple: the
// order of octants x | y<<1 | z<<2 in svdag/layout.h, so sorting by code is depth-first
// order of the octree.
#pragma once
#include <cstdint>

namespace voxray::svdag_build {

// Spreads the low 21 bits of v to every third bit.
inline std::uint64_t spread3(std::uint32_t v) {
    std::uint64_t x = v & 0x1FFFFFu;
    x = (x | (x << 32)) & 0x1F00000000FFFFull;
    x = (x | (x << 16)) & 0x1F0000FF0000FFull;
    x = (x | (x << 8)) & 0x100F00F00F00F00Full;
    x = (x | (x << 4)) & 0x10C30C30C30C30C3ull;
    x = (x | (x << 2)) & 0x1249249249249249ull;
    return x;
}

inline std::uint64_t morton3(std::uint32_t x, std::uint32_t y, std::uint32_t z) {
    return spread3(x) | (spread3(y) << 1) | (spread3(z) << 2);
}

}  // namespace voxray::svdag_build
