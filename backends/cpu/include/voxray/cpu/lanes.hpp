// The portable kernels compiled as C++, three times: with scalar lanes (the reference
// path, `cpu-scalar`), and with SIMD lanes (GCC vector types, one ray per lane) 8 wide
// (AVX2) and 16 wide (AVX-512, picked at run time where the CPU has it). All come from
// the very same kernel files; only the lane types and helpers differ.
//
// This header sets up both lane namespaces with the shared dialect (ray, DDA). Each
// structure's kernel joins them through voxray/cpu/kernel_lanes.inc, which its host header
// includes (by kernels/kernel_tag.inc) in programs that link voxray::cpu: kernel files have
// no include guards, so each is included once per namespace.
#pragma once
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <utility>

// The SIMD lane sets are compiled here unless the program links voxray::kernels, which
// holds the SIMD streams of every registered structure: then only the scalar lanes are
// (tracer::closest_hit of one ray, the world's frame passes). A file that works with the
// lanes themselves may define VOXRAY_CPU_SIMD_LANES 1.
#if !defined(VOXRAY_CPU_SIMD_LANES)
#if defined(VOXRAY_CPU_KERNELS_LINKED)
#define VOXRAY_CPU_SIMD_LANES 0
#else
#define VOXRAY_CPU_SIMD_LANES 1
#endif
#endif
#if VOXRAY_CPU_SIMD_LANES
#include <immintrin.h>
#endif

#include "voxray/kernels/prelude.h"

namespace voxray::kernels {


namespace scalar {
using uint = std::uint32_t;
using vx_f32 = float;
using vx_i32 = std::int32_t;
using vx_u32 = std::uint32_t;
using vx_mask = bool;
inline constexpr int width = 1;
// One structure kernel's state machine (load, begin, step, finish, status, trace) in this
// lane set; specialized by VOXRAY_KERNEL_LANES (kernels/kernel_tag.inc).
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
inline float vx_bits_f(std::uint32_t x) { return std::bit_cast<float>(x); }
inline float vx_floor(float x) { return std::floor(x); }
inline float vx_sqrt(float x) { return std::sqrt(x); }  // appearance/compact_record.h, record.h
inline float vx_f32_splat(float x) { return x; }
inline std::int32_t vx_i32_splat(std::int32_t x) { return x; }
inline std::uint32_t vx_u32_splat(std::uint32_t x) { return x; }
// min/max written as selects so that scalar and SIMD lanes round and order identically.
inline float vx_fmin(float a, float b) { return a < b ? a : b; }
inline float vx_fmax(float a, float b) { return a > b ? a : b; }
inline bool vx_any(bool m) { return m; }
template <class State>
inline void vx_select_state_into(bool m, const State& a, State& into) {
    if (m) into = a;
}

#include "voxray/kernels/dialect.h"

// Scalar code over the lanes of m in turn (see simd_lanes.inc); here one lane.
template <class F>
inline vx_hit vx_each_lane(bool m, const vx_ray& r, const vx_hit& h, F&& f) {
    return m ? f(r, h) : h;
}

// Frame words (world/frame/passes.h, scalar lanes only): one item per call, threads share the
// frame, so counters and the visibility buffer use the same atomics as the GPUs.
typedef std::uint64_t __attribute__((may_alias)) vx_frame_u64;
inline std::uint32_t vx_frame_load(const std::uint32_t* f, std::uint32_t i) { return __atomic_load_n(f + i, __ATOMIC_RELAXED); }
inline void vx_frame_store(std::uint32_t* f, std::uint32_t i, std::uint32_t v) { __atomic_store_n(f + i, v, __ATOMIC_RELAXED); }
inline std::uint32_t vx_atomic_add(std::uint32_t* f, std::uint32_t i, std::uint32_t v) {
    return __atomic_fetch_add(f + i, v, __ATOMIC_RELAXED);
}
inline void vx_atomic_max64(std::uint32_t* f, std::uint32_t i, std::uint32_t hi, std::uint32_t lo) {
    auto* word = reinterpret_cast<vx_frame_u64*>(f + i);  // i is even: 8-byte aligned
    std::uint64_t v = (std::uint64_t(hi) << 32) | lo, old = __atomic_load_n(word, __ATOMIC_RELAXED);
    while (old < v && !__atomic_compare_exchange_n(word, &old, v, true, __ATOMIC_RELAXED, __ATOMIC_RELAXED)) {
    }
}
}  // namespace scalar

// Each SIMD lane set is compiled for its own ISA whatever the build flags (GCC: a target
// pragma; clang: a target attribute applied to every function), and runs only where
// cpu_has_avx2() / cpu_has_avx512() say the CPU has it: one binary uses AVX-512 where it
// exists and AVX2 elsewhere, as Embree does.
#if defined(__clang__)
#define VOXRAY_TARGET_BEGIN_(isa) _Pragma(VOXRAY_TARGET_STR_(clang attribute push(__attribute__((target(isa))), apply_to = function)))
#define VOXRAY_TARGET_END_ _Pragma("clang attribute pop")
#else
#define VOXRAY_TARGET_BEGIN_(isa) _Pragma("GCC push_options") _Pragma(VOXRAY_TARGET_STR_(GCC target(isa)))
#define VOXRAY_TARGET_END_ _Pragma("GCC pop_options")
#endif
#define VOXRAY_TARGET_STR_(x) #x
#define VOXRAY_AVX2_BEGIN VOXRAY_TARGET_BEGIN_("avx2")
#define VOXRAY_AVX2_END VOXRAY_TARGET_END_
#define VOXRAY_AVX512_BEGIN VOXRAY_TARGET_BEGIN_("avx512f,avx512dq,avx512bw,avx512vl")
#define VOXRAY_AVX512_END VOXRAY_TARGET_END_

inline bool cpu_has_avx2() {
    static const bool has = __builtin_cpu_supports("avx2");
    return has;
}
inline bool cpu_has_avx512() {
    static const bool has = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq") &&
                            __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512vl");
    return has;
}

}  // namespace voxray::kernels

#if VOXRAY_CPU_SIMD_LANES
#define VOXRAY_LANE_SET_BODY "voxray/cpu/simd_lanes.inc"
#include "voxray/cpu/each_lane_set.inc"
#endif

// The kernel_lanes specialization of structure kernel `s` in the current lane
// namespace: the functions every kernel names vx_<s>_load/begin/step/finish/status/trace
// (types come from their signatures), and vx_<s>_resume where a kernel has one. `mode`
// arguments are VX_MODE_* constants at every call site, so each mode compiles to its own
// code (any-hit skips what it need not read).
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
        /* Lanes m's state for new rays r after `old` ended: begin, then vx_<s>_resume where the   \
           kernel has one (it starts the new walks from what the old ones found). */             \
        template <class Header>                                                                                  \
        __attribute__((always_inline)) static state restart(const Header& g, const vx_ray& r, const state& old, \
                                                            vx_mask m) {                                         \
            if constexpr (requires { vx_##s##_resume(g, old, old, m); })                                         \
                return vx_##s##_resume(g, old, vx_##s##_begin(g, r), m);                                         \
            else                                                                                                 \
                return vx_##s##_begin(g, r);                                                                     \
        }                                                                                                        \
        __attribute__((always_inline)) static state step(const std::uint32_t* b, const header& g,               \
                                                         const state& st) {                                      \
            return vx_##s##_step(b, g, st);                                                                      \
        }                                                                                                        \
        template <std::uint32_t Mode>                                                                            \
        __attribute__((always_inline)) static vx_hit finish(const std::uint32_t* b, const header& g,            \
                                                            const state& st, const vx_ray& r) {                  \
            return vx_##s##_finish(b, g, st, r, Mode);                                                           \
        }                                                                                                        \
        __attribute__((always_inline)) static vx_u32 status(const state& st) { return vx_##s##_status(st); }    \
        template <std::uint32_t Mode>                                                                            \
        __attribute__((always_inline)) static vx_hit trace(const std::uint32_t* b, const vx_ray& r) {           \
            return vx_##s##_trace(b, r, Mode);                                                                   \
        }                                                                                                        \
    };
