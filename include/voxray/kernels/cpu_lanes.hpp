// The portable kernels compiled as C++, twice: once with scalar lanes (the reference
// path, `cpu-scalar`) and once with SIMD lanes (GCC vector types, one ray per lane).
// Both come from the very same kernel files; only the lane types and helpers differ.
//
// This header sets up both lane namespaces with the shared dialect (ray, DDA). Each
// structure's kernel joins them through kernels/cpu_kernel.inc, which its host header
// includes: kernel files have no include guards, so each is included once per namespace.
#pragma once
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <type_traits>
#include <utility>

#include <immintrin.h>

#include "voxray/kernels/prelude.h"

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
// One structure kernel's state machine (load, begin, step, finish, status, trace) in this
// lane set; specialized by VOXRAY_KERNEL_LANES (kernels/cpu_kernel.inc).
template <class Kernel>
struct kernel_lanes;

inline std::uint32_t vx_load(const std::uint32_t* b, std::uint32_t i) { return b[i]; }
inline std::uint32_t vx_gather(const std::uint32_t* b, std::uint32_t i) { return b[i]; }
inline std::uint32_t vx_gather_masked(const std::uint32_t* b, bool m, std::uint32_t i) { return m ? b[i] : 0u; }
inline float vx_i2f(std::int32_t x) { return float(x); }
inline float vx_u2f(std::uint32_t x) { return float(x); }
inline std::int32_t vx_f2i(float x) { return std::int32_t(x); }
inline std::uint32_t vx_i2u(std::int32_t x) { return std::uint32_t(x); }
inline std::int32_t vx_u2i(std::uint32_t x) { return std::int32_t(x); }
inline std::uint32_t vx_f_bits(float x) { return std::bit_cast<std::uint32_t>(x); }
inline float vx_floor(float x) { return std::floor(x); }
inline float vx_f32_splat(float x) { return x; }
inline std::int32_t vx_i32_splat(std::int32_t x) { return x; }
inline std::uint32_t vx_u32_splat(std::uint32_t x) { return x; }
// min/max written as selects so that scalar and SIMD lanes round and order identically.
inline float vx_fmin(float a, float b) { return a < b ? a : b; }
inline float vx_fmax(float a, float b) { return a > b ? a : b; }
inline bool vx_any(bool m) { return m; }
template <class State>
inline State vx_select_state(bool m, const State& a, const State& b) { return m ? a : b; }

#include "voxray/kernels/ray.h"
#include "voxray/kernels/dda.h"
}  // namespace scalar

namespace simd {
using uint = std::uint32_t;
inline constexpr int width = simd_width;
template <class Kernel>
struct kernel_lanes;
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
// b[i] in the lanes of m, 0 in the others, which load nothing (no load at all when m is
// empty): the pattern of every lookup only some lanes need.
inline vx_u32 vx_gather_masked(const std::uint32_t* b, vx_mask m, vx_u32 i) {
    if (!vx_any(m)) return vx_u32{};
#if defined(__AVX512F__) && !defined(VOXRAY_SCALAR_GATHER)
    __mmask16 k = _mm512_test_epi32_mask((__m512i)m, (__m512i)m);
    return (vx_u32)_mm512_mask_i32gather_epi32(_mm512_setzero_si512(), k, (__m512i)i, reinterpret_cast<const int*>(b), 4);
#elif defined(__AVX2__) && !defined(VOXRAY_SCALAR_GATHER)
    return (vx_u32)_mm256_mask_i32gather_epi32(_mm256_setzero_si256(), reinterpret_cast<const int*>(b), (__m256i)i,
                                               (__m256i)m, 4);
#else
    vx_u32 r;
    for (int k = 0; k < width; ++k) r[k] = m[k] ? b[i[k]] : 0u;
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
inline vx_f32 vx_f32_splat(float x) { return vx_f32{} + x; }
inline vx_i32 vx_i32_splat(std::int32_t x) { return vx_i32{} + x; }
inline vx_u32 vx_u32_splat(std::uint32_t x) { return vx_u32{} + x; }
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

// Per lane: a where m is set, else b, for a whole kernel state. Kernel states hold
// per-lane fields only (lane vectors of 32-bit values, or arrays of them), so a state
// is a row of lane vectors and one blend per row merges it: no per-structure select.
template <class State>
inline State vx_select_state(vx_mask m, const State& a, const State& b) {
    static_assert(std::is_trivially_copyable_v<State> && sizeof(State) % sizeof(vx_u32) == 0 &&
                      alignof(State) == alignof(vx_u32),
                  "a kernel state must consist of lane vectors only (no uniform fields)");
    using rows = std::array<vx_u32, sizeof(State) / sizeof(vx_u32)>;
    rows ra = std::bit_cast<rows>(a), rb = std::bit_cast<rows>(b), out;
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = m ? ra[i] : rb[i];
    return std::bit_cast<State>(out);
}

#include "voxray/kernels/ray.h"
#include "voxray/kernels/dda.h"
}  // namespace simd

}  // namespace voxray::kernels

// The kernel_lanes specialization of structure kernel `s` in the current lane
// namespace: the functions every kernel names vx_<s>_load/begin/step/finish/status/trace
// (types come from their signatures). `mode` arguments are VX_MODE_* constants at every
// call site, so each mode compiles to its own code (any-hit skips what it need not read).
#define VOXRAY_KERNEL_LANES(s) VOXRAY_KERNEL_LANES_(s)
#define VOXRAY_KERNEL_LANES_(s)                                                                                  \
    template <>                                                                                                  \
    struct kernel_lanes<s##_kernel> {                                                                            \
        using header = decltype(vx_##s##_load(static_cast<const std::uint32_t*>(nullptr)));                     \
        using state = decltype(vx_##s##_begin(std::declval<header>(), std::declval<vx_ray>()));                  \
        __attribute__((always_inline)) static header load(const std::uint32_t* b) { return vx_##s##_load(b); }  \
        __attribute__((always_inline)) static state begin(const header& g, const vx_ray& r) {                   \
            return vx_##s##_begin(g, r);                                                                         \
        }                                                                                                        \
        __attribute__((always_inline)) static state step(const std::uint32_t* b, const header& g,               \
                                                         const state& st) {                                      \
            return vx_##s##_step(b, g, st);                                                                      \
        }                                                                                                        \
        template <std::uint32_t Mode>                                                                            \
        __attribute__((always_inline)) static vx_hit finish(const std::uint32_t* b, const header& g,            \
                                                            const state& st) {                                   \
            return vx_##s##_finish(b, g, st, Mode);                                                              \
        }                                                                                                        \
        __attribute__((always_inline)) static vx_u32 status(const state& st) { return vx_##s##_status(st); }    \
        template <std::uint32_t Mode>                                                                            \
        __attribute__((always_inline)) static vx_hit trace(const std::uint32_t* b, const vx_ray& r) {           \
            return vx_##s##_trace(b, r, Mode);                                                                   \
        }                                                                                                        \
    };
