// Which bytes of a 64-byte row of materials equal one material, as a 64-bit mask: the
// mesher's merge test for faces whose plane rows run along x (Y and Z faces), one compare
// for a whole run instead of one per face. AVX2 where the build has it, else 8 bytes at a time.
#pragma once
#include <cstdint>
#include <cstring>

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace voxray::meshing {

inline std::uint64_t same_material_mask(const std::uint8_t* row, std::uint8_t material) {
#if defined(__AVX2__)
    const __m256i k = _mm256_set1_epi8(char(material));
    __m256i lo = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row));
    __m256i hi = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(row + 32));
    auto same_lo = std::uint32_t(_mm256_movemask_epi8(_mm256_cmpeq_epi8(lo, k)));
    auto same_hi = std::uint32_t(_mm256_movemask_epi8(_mm256_cmpeq_epi8(hi, k)));
    return std::uint64_t(same_lo) | (std::uint64_t(same_hi) << 32);
#else
    constexpr std::uint64_t low7 = 0x7F7F7F7F7F7F7F7Full;
    const std::uint64_t k = 0x0101010101010101ull * material;
    std::uint64_t mask = 0;
    for (int part = 0; part < 8; ++part) {
        std::uint64_t w;
        std::memcpy(&w, row + part * 8, 8);
        w ^= k;  // 0 where equal
        std::uint64_t differs = (((w & low7) + low7) | w) & ~low7;
        mask |= ((~differs & ~low7) * 0x0002040810204081ull >> 56) << (part * 8);
    }
    return mask;
#endif
}

}  // namespace voxray::meshing
