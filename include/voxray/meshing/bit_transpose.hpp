// 64 x 64 bit matrix transpose in place: afterwards bit j of a[i] is what bit i of a[j] was.
// Six rounds of block swaps (32, 16, ..., 1 wide), the recursive method of Hacker's Delight
// written for bit 0 = column 0.
#pragma once
#include <cstdint>

namespace voxray::meshing {

inline void transpose64(std::uint64_t* a) {
    std::uint64_t m = 0x00000000FFFFFFFFull;
    for (int j = 32; j != 0; j >>= 1, m ^= m << j)
        for (int k = 0; k < 64; k = ((k | j) + 1) & ~j) {
            std::uint64_t t = ((a[k] >> j) ^ a[k | j]) & m;
            a[k] ^= t << j;
            a[k | j] ^= t;
        }
}

}  // namespace voxray::meshing
