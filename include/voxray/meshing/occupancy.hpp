// Occupancy masks from material bytes: 64 bytes (one row of a chunk along x) become one
// 64-bit word, bit x set where byte x is not 0. AVX-512 tests a row in one instruction
// (vptestmb), AVX2 in two compares; the scalar fallback folds 8 bytes at a time. The path
// is picked once at run time, so a binary built for x86-64-v3 still uses AVX-512 where
// the CPU has it.
#pragma once
#include <cstdint>
#include <cstring>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace voxray::meshing {

namespace occupancy_detail {

inline void rows_scalar(const std::uint8_t* bytes, int count, std::uint64_t* out) {
    constexpr std::uint64_t low7 = 0x7F7F7F7F7F7F7F7Full;
    for (int r = 0; r < count; ++r) {
        std::uint64_t row = 0;
        for (int part = 0; part < 8; ++part) {
            std::uint64_t w;
            std::memcpy(&w, bytes + r * 64 + part * 8, 8);
            // High bit of each byte set iff the byte is not 0, then gathered into 8 bits.
            std::uint64_t high = (((w & low7) + low7) | w) & ~low7;
            row |= ((high * 0x0002040810204081ull) >> 56) << (part * 8);
        }
        out[r] = row;
    }
}

#if defined(__x86_64__)
__attribute__((target("avx512bw"))) inline void rows_avx512(const std::uint8_t* bytes, int count, std::uint64_t* out) {
    for (int r = 0; r < count; ++r) {
        __m512i v = _mm512_loadu_si512(bytes + r * 64);
        out[r] = _mm512_test_epi8_mask(v, v);
    }
}

__attribute__((target("avx2"))) inline void rows_avx2(const std::uint8_t* bytes, int count, std::uint64_t* out) {
    const __m256i zero = _mm256_setzero_si256();
    for (int r = 0; r < count; ++r) {
        __m256i lo = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(bytes + r * 64));
        __m256i hi = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(bytes + r * 64 + 32));
        auto empty_lo = std::uint32_t(_mm256_movemask_epi8(_mm256_cmpeq_epi8(lo, zero)));
        auto empty_hi = std::uint32_t(_mm256_movemask_epi8(_mm256_cmpeq_epi8(hi, zero)));
        out[r] = ~(std::uint64_t(empty_lo) | (std::uint64_t(empty_hi) << 32));
    }
}
#endif

enum class path { scalar, avx2, avx512 };

inline path best_path() {
#if defined(__x86_64__)
    static const path chosen = __builtin_cpu_supports("avx512bw") ? path::avx512
                               : __builtin_cpu_supports("avx2")   ? path::avx2
                                                                  : path::scalar;
    return chosen;
#else
    return path::scalar;
#endif
}

}  // namespace occupancy_detail

// `count` rows of 64 bytes at `bytes` -> `count` words at `out`.
inline void occupancy_rows(const std::uint8_t* bytes, int count, std::uint64_t* out) {
    using namespace occupancy_detail;
#if defined(__x86_64__)
    switch (best_path()) {
        case path::avx512: return rows_avx512(bytes, count, out);
        case path::avx2: return rows_avx2(bytes, count, out);
        case path::scalar: break;
    }
#endif
    rows_scalar(bytes, count, out);
}

inline const char* occupancy_path_name() {
    switch (occupancy_detail::best_path()) {
        case occupancy_detail::path::avx512: return "avx512";
        case occupancy_detail::path::avx2: return "avx2";
        default: return "scalar";
    }
}

}  // namespace voxray::meshing
