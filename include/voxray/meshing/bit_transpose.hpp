// 64 x 64 bit matrix transpose in place: afterwards bit j of a[i] is what bit i of a[j] was.
//
// Portable: six rounds of block swaps (32, 16, ..., 1 wide), the recursive method of
// Hacker's Delight written for bit 0 = column 0; about 1,300 operations.
// GFNI (with AVX-512 VBMI), picked at run time: the matrix is 8 x 8 blocks of 8 x 8 bits.
//   1. per 8 rows (one register), a byte permute puts block (I, J) of the rows into qword J,
//      its rows reversed;
//   2. gf2p8affineqb against the identity transposes every 8 x 8 bit block (its row order
//      is reversed, which step 1 undid in advance);
//   3. qword J of each of the 8 registers is gathered into output register J, and a byte
//      permute interleaves them into rows. About 50 instructions.
#pragma once
#include <cstdint>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace voxray::meshing {

inline void transpose64_scalar(std::uint64_t* a) {
    std::uint64_t m = 0x00000000FFFFFFFFull;
    for (int j = 32; j != 0; j >>= 1, m ^= m << j)
        for (int k = 0; k < 64; k = ((k | j) + 1) & ~j) {
            std::uint64_t t = ((a[k] >> j) ^ a[k | j]) & m;
            a[k] ^= t << j;
            a[k | j] ^= t;
        }
}

#if defined(__x86_64__)
// GCC 12 reports the undefined start value inside its own permute intrinsics as uninitialized.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wuninitialized"
__attribute__((target("avx512f,avx512bw,avx512vbmi,gfni"))) inline void transpose64_gfni(std::uint64_t* a) {
    // Byte permutes of an 8 x 8 byte matrix (position 8 * row + column): to_blocks sends
    // byte J of row k to qword J, byte 7 - k; to_rows sends byte t of qword I to row t, byte I.
    alignas(64) static const std::uint8_t to_blocks[64] = {
#define VX_ROW(J) 56 + J, 48 + J, 40 + J, 32 + J, 24 + J, 16 + J, 8 + J, J
        VX_ROW(0), VX_ROW(1), VX_ROW(2), VX_ROW(3), VX_ROW(4), VX_ROW(5), VX_ROW(6), VX_ROW(7)
#undef VX_ROW
    };
    alignas(64) static const std::uint8_t to_rows[64] = {
#define VX_ROW(t) t, 8 + t, 16 + t, 24 + t, 32 + t, 40 + t, 48 + t, 56 + t
        VX_ROW(0), VX_ROW(1), VX_ROW(2), VX_ROW(3), VX_ROW(4), VX_ROW(5), VX_ROW(6), VX_ROW(7)
#undef VX_ROW
    };
    const __m512i blocks = _mm512_load_si512(to_blocks), rows = _mm512_load_si512(to_rows);
    const __m512i identity = _mm512_set1_epi64(std::int64_t(0x8040201008040201ull));
    alignas(64) std::uint64_t tmp[64];
    for (int i = 0; i < 8; ++i) {
        __m512i x = _mm512_permutexvar_epi8(blocks, _mm512_loadu_si512(a + 8 * i));
        _mm512_store_si512(tmp + 8 * i, _mm512_gf2p8affine_epi64_epi8(identity, x, 0));
    }
    const __m512i stride = _mm512_setr_epi64(0, 8, 16, 24, 32, 40, 48, 56);
    for (int j = 0; j < 8; ++j) {
        __m512i g = _mm512_i64gather_epi64(_mm512_add_epi64(stride, _mm512_set1_epi64(j)), tmp, 8);
        _mm512_storeu_si512(a + 8 * j, _mm512_permutexvar_epi8(rows, g));
    }
}
#pragma GCC diagnostic pop
#endif

inline bool transpose64_has_gfni() {
#if defined(__x86_64__)
    static const bool has = __builtin_cpu_supports("gfni") && __builtin_cpu_supports("avx512vbmi") &&
                            __builtin_cpu_supports("avx512bw");
    return has;
#else
    return false;
#endif
}

inline void transpose64(std::uint64_t* a) {
#if defined(__x86_64__)
    if (transpose64_has_gfni()) return transpose64_gfni(a);
#endif
    transpose64_scalar(a);
}

}  // namespace voxray::meshing
