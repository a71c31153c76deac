// The portable kernels compiled as C++, twice: once with scalar lanes (the reference
// path, `cpu-scalar`) and once with SIMD lanes (GCC vector types, one ray per lane).
// Both come from the very same kernel files; only the lane types and helpers differ.
//
// The kernel files have no include guards: this header includes each of them once per
// lane namespace, in dependency order. A new structure adds its kernel file to both lists
// below and a line to cpu_dispatch.inc.
#pragma once
#include <bit>
#include <cmath>
#include <cstdint>

#include <immintrin.h>

#include "voxray/kernels/kernel_ids.hpp"
#include "voxray/kernels/prelude.h"
#include "voxray/layout/brickmap_layout.h"
#include "voxray/layout/dense_grid_layout.h"

namespace voxray::kernels {

// Lanes per SIMD packet: 16 with AVX-512, else 8 (AVX2 and x86-64-v3).
#if defined(__AVX512F__)
inline constexpr int simd_width = 16;
#else
inline constexpr int simd_width = 8;
#endif

namespace scalar {
using uint = std::uint32_t;
using vx_f32 = float;
using vx_i32 = std::int32_t;
using vx_u32 = std::uint32_t;
using vx_mask = bool;
inline constexpr int width = 1;

inline std::uint32_t vx_load(const std::uint32_t* b, std::uint32_t i) { return b[i]; }
inline std::uint32_t vx_gather(const std::uint32_t* b, std::uint32_t i) { return b[i]; }
inline float vx_i2f(std::int32_t x) { return float(x); }
inline float vx_u2f(std::uint32_t x) { return float(x); }
inline std::int32_t vx_f2i(float x) { return std::int32_t(x); }
inline std::uint32_t vx_i2u(std::int32_t x) { return std::uint32_t(x); }
inline std::int32_t vx_u2i(std::uint32_t x) { return std::int32_t(x); }
inline std::uint32_t vx_f_bits(float x) { return std::bit_cast<std::uint32_t>(x); }
inline float vx_floor(float x) { return std::floor(x); }
// min/max written as selects so that scalar and SIMD lanes round and order identically.
inline float vx_fmin(float a, float b) { return a < b ? a : b; }
inline float vx_fmax(float a, float b) { return a > b ? a : b; }
inline bool vx_any(bool m) { return m; }

#include "voxray/kernels/ray.h"
#include "voxray/kernels/dda.h"
#include "voxray/kernels/dense_grid.h"
#include "voxray/kernels/brickmap.h"
#include "voxray/kernels/cpu_dispatch.inc"
}  // namespace scalar

namespace simd {
using uint = std::uint32_t;
inline constexpr int width = simd_width;
typedef float vx_f32 __attribute__((vector_size(4 * simd_width)));
typedef std::int32_t vx_i32 __attribute__((vector_size(4 * simd_width)));
typedef std::uint32_t vx_u32 __attribute__((vector_size(4 * simd_width)));
using vx_mask = vx_i32;  // all ones or zero per lane, as vector comparisons produce

inline std::uint32_t vx_load(const std::uint32_t* b, std::uint32_t i) { return b[i]; }
// Per-lane load. Indices are words; blobs are limited to 2^31 words (8 GiB) for this.
inline vx_u32 vx_gather(const std::uint32_t* b, vx_u32 i) {
#if defined(__AVX512F__) && !defined(VOXRAY_SCALAR_GATHER)
    return (vx_u32)_mm512_i32gather_epi32((__m512i)i, reinterpret_cast<const int*>(b), 4);
#elif defined(__AVX2__) && !defined(VOXRAY_SCALAR_GATHER)
    return (vx_u32)_mm256_i32gather_epi32(reinterpret_cast<const int*>(b), (__m256i)i, 4);
#else
    vx_u32 r;
    for (int k = 0; k < width; ++k) r[k] = b[i[k]];
    return r;
#endif
}
inline float vx_i2f(std::int32_t x) { return float(x); }
inline vx_f32 vx_i2f(vx_i32 x) { return __builtin_convertvector(x, vx_f32); }
inline vx_i32 vx_f2i(vx_f32 x) { return __builtin_convertvector(x, vx_i32); }
inline std::uint32_t vx_i2u(std::int32_t x) { return std::uint32_t(x); }
inline vx_u32 vx_i2u(vx_i32 x) { return (vx_u32)x; }
inline std::int32_t vx_u2i(std::uint32_t x) { return std::int32_t(x); }
inline vx_i32 vx_u2i(vx_u32 x) { return (vx_i32)x; }
inline vx_u32 vx_f_bits(vx_f32 x) { return (vx_u32)x; }
inline vx_f32 vx_floor(vx_f32 x) {
#if defined(__AVX512F__)
    return (vx_f32)_mm512_roundscale_ps((__m512)x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
#elif defined(__AVX__)
    return (vx_f32)_mm256_floor_ps((__m256)x);
#else
    vx_f32 r;
    for (int k = 0; k < width; ++k) r[k] = std::floor(x[k]);
    return r;
#endif
}
inline vx_f32 vx_fmin(vx_f32 a, vx_f32 b) { return a < b ? a : b; }
inline vx_f32 vx_fmax(vx_f32 a, vx_f32 b) { return a > b ? a : b; }
inline vx_f32 vx_fmin(vx_f32 a, float b) { return a < b ? a : b; }
inline vx_f32 vx_fmax(vx_f32 a, float b) { return a > b ? a : b; }
inline bool vx_any(vx_i32 m) {
#if defined(__AVX512F__)
    return _mm512_test_epi32_mask((__m512i)m, (__m512i)m) != 0;
#elif defined(__AVX__)
    return _mm256_movemask_ps((__m256)m) != 0;
#else
    for (int k = 0; k < width; ++k)
        if (m[k]) return true;
    return false;
#endif
}

#include "voxray/kernels/ray.h"
#include "voxray/kernels/dda.h"
#include "voxray/kernels/dense_grid.h"
#include "voxray/kernels/brickmap.h"
#include "voxray/kernels/cpu_dispatch.inc"
}  // namespace simd

}  // namespace voxray::kernels
