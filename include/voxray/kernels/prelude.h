/* The portable kernel dialect. One traversal source compiles as:
 *   VX_DIALECT_CPP    C++ scalar lanes   (types: float, int32_t, bool)
 *   VX_DIALECT_CPP    C++ SIMD lanes     (GCC vector types; see cpu/lanes.hpp)
 *   VX_DIALECT_OPENCL OpenCL C 1.2       (PoCL; source embedded at build time)
 *   VX_DIALECT_GLSL   GLSL 4.50 -> SPIR-V (glslang at build time; buffers by device address)
 *
 * Rules for kernel code (so that the SIMD mode stays one source with the GPU modes):
 *  - per-lane types are vx_f32, vx_i32, vx_u32 and vx_mask; uniform values use float/uint/int;
 *  - no `if` on per-lane values inside a step function: use vx_sel(mask, a, b);
 *  - conversions and loads go through the vx_* helpers below; lane-typed constants are
 *    vx_f32_splat / vx_i32_splat / vx_u32_splat(x), a lookup only some lanes need is
 *    vx_gather_masked(blob, mask, index) (0 in the other lanes, which load nothing);
 *  - structs are passed by value and returned, which all three languages allow; where a
 *    state is too big to copy, a function takes VX_INOUT(T) s, reads and writes
 *    VX_REF(s).field, and is called with VX_ADDR(state) (a reference in C++ and GLSL's
 *    inout, a pointer in OpenCL C, which has no references);
 *  - kernel states hold per-lane fields only: the CPU stream merges them lane by lane
 *    generically (vx_select_state_into in cpu/simd_lanes.inc), so no kernel writes a select;
 *  - an entry point's parameter that one structure does not need is marked VX_UNUSED(p);
 *  - a structure kernel `s` names its entry points vx_<s>_load, _begin, _step, _finish,
 *    _status and _trace; `mode` arguments are VX_MODE_* constants at every call site.
 * In C++ the helpers are functions defined per lane namespace (voxray/cpu/lanes.hpp); here they
 * are macros for the GPU dialects.
 */
#ifndef VOXRAY_KERNELS_PRELUDE_H
#define VOXRAY_KERNELS_PRELUDE_H

#include "voxray/core/ray_hit_layout.h"

#define vx_sel(m, a, b) ((m) ? (a) : (b))

#if defined(VX_DIALECT_OPENCL)
#pragma OPENCL FP_CONTRACT OFF
#define VX_FN static inline
#define VX_STRUCT(name) typedef struct name {
#define VX_END_STRUCT(name) } name;
#define VX_BLOB __global const uint*
#define VX_INF INFINITY
typedef float vx_f32;
typedef int vx_i32;
typedef uint vx_u32;
typedef bool vx_mask;
#define vx_load(b, i) ((b)[(i)])
#define vx_gather(b, i) ((b)[(i)])
#define vx_gather_masked(b, m, i) ((m) ? (b)[(i)] : 0u)
#define vx_blob_at(b, n) ((b) + (n))
#define vx_f32_splat(x) ((float)(x))
#define vx_i32_splat(x) ((int)(x))
#define vx_u32_splat(x) ((uint)(x))
#define VX_INOUT(T) T*
#define VX_REF(p) (*(p))
#define VX_ADDR(x) (&(x))
#define VX_UNUSED(x) ((void)(x))
#define vx_i2f(x) convert_float(x)
#define vx_u2f(x) convert_float(x)
#define vx_f2i(x) convert_int(x)
#define vx_i2u(x) as_uint(x)
#define vx_u2i(x) as_int(x)
#define vx_f_bits(x) as_uint(x)
#define vx_bits_f(x) as_float(x)
#define vx_floor(x) floor(x)
#define vx_log2(x) log2(x)
#define vx_sqrt(x) sqrt(x)
#define vx_any(m) (m)
/* Frame words (read-write, one item per work-item; world/frame/passes.h), and their atomics. */
#define VX_FRAME __global uint*
#define VX_PRECISE
#define vx_frame_load(f, i) ((f)[(i)])
#define vx_frame_store(f, i, v) ((f)[(i)] = (v))
#define vx_atomic_add(f, i, v) atomic_add(&(f)[(i)], (v))
#if defined(cl_khr_int64_extended_atomics)
#define vx_atomic_max64(f, i, hi, lo) \
    atom_max((volatile __global ulong*)&(f)[(i)], ((ulong)(hi) << 32) | (ulong)(lo))
#else
/* Without 64-bit atomics a program with frame passes still builds, for tracing; the engine
 * refuses to run its passes (opencl/engine.hpp). */
#define vx_atomic_max64(f, i, hi, lo) ((void)(f), (void)(i), (void)(hi), (void)(lo))
#endif
/* Spelled like the C++ lanes (cpu/lanes.hpp), not as OpenCL fmin/fmax: those
 * return the other operand for a NaN (the C++ select returns the second) and leave the
 * sign of min(+0, -0) to the device, so t could be -0 on one backend and +0 on another. */
static inline float vx_fmin(float a, float b) { return a < b ? a : b; }
static inline float vx_fmax(float a, float b) { return a > b ? a : b; }

#elif defined(VX_DIALECT_GLSL)
#define VX_FN
#define VX_STRUCT(name) struct name {
#define VX_END_STRUCT(name) };
#define VX_BLOB vx_words
#define VX_INF uintBitsToFloat(0x7f800000u)
#define vx_f32 float
#define vx_i32 int
#define vx_u32 uint
#define vx_mask bool
#define vx_load(b, i) ((b).w[(i)])
#define vx_gather(b, i) ((b).w[(i)])
#define vx_gather_masked(b, m, i) ((m) ? (b).w[(i)] : 0u)
#define vx_f32_splat(x) float(x)
#define vx_i32_splat(x) int(x)
#define vx_u32_splat(x) uint(x)
#define VX_INOUT(T) inout T
#define VX_REF(p) (p)
#define VX_ADDR(x) (x)
#define VX_UNUSED(x)
#define vx_i2f(x) float(x)
#define vx_u2f(x) float(x)
#define vx_f2i(x) int(x)
#define vx_i2u(x) uint(x)
#define vx_u2i(x) int(x)
#define vx_f_bits(x) floatBitsToUint(x)
#define vx_bits_f(x) uintBitsToFloat(x)
#define vx_floor(x) floor(x)
#define vx_log2(x) log2(x)
#define vx_sqrt(x) sqrt(x)
#define vx_any(m) (m)
/* Frame words by address (world/frame/passes.h); the 64-bit view needs VX_INT64_ATOMICS
 * (backends/vulkan/shaders/dialect.glsl). `precise` keeps a*b+c two roundings, as in C++. */
#define VX_FRAME uvec2
#define VX_PRECISE precise
#define vx_frame_load(f, i) (vx_words_rw(f).w[(i)])
#define vx_frame_store(f, i, v) (vx_words_rw(f).w[(i)] = (v))
#define vx_atomic_add(f, i, v) atomicAdd(vx_words_rw(f).w[(i)], (v))
#define vx_atomic_max64(f, i, hi, lo) atomicMax(vx_words64(f).w[(i) >> 1], packUint2x32(uvec2((lo), (hi))))
/* Spelled like the C++ lanes (cpu/lanes.hpp), not as GLSL min/max: those leave
 * the result for a NaN operand undefined (lavapipe returns the other operand, the C++
 * select returns b), so a NaN would steer the GPU and the CPU down different cells. */
float vx_fmin(float a, float b) { return a < b ? a : b; }
float vx_fmax(float a, float b) { return a > b ? a : b; }
/* Structure data, rays and hits are reached by buffer device address: no descriptor
 * range limit (lavapipe's maxStorageBufferRange is 128 MiB) applies to them. */
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer vx_words { uint w[]; };
/* The words from word n of b on (a structure inside another's blob: a scene's world). */
vx_words vx_blob_at(vx_words b, uint n) {
    uvec2 a = uvec2(b);
    uint lo = a.x + n * 4u;
    return vx_words(uvec2(lo, a.y + (lo < a.x ? 1u : 0u)));
}
/* Kernel code must not use GLSL keywords or reserved words (out, active, input...) or
 * OpenCL C ones (local, global, kernel...) as names. */

#else /* C++: the including file (voxray/cpu/lanes.hpp) supplies types and helpers. */
#define VX_DIALECT_CPP 1
#define VX_FN inline __attribute__((always_inline))
#define VX_STRUCT(name) struct name {
#define VX_END_STRUCT(name) };
#define VX_BLOB const std::uint32_t*
#define vx_blob_at(b, n) ((b) + (n))
#define VX_INF __builtin_inff()
#define VX_INOUT(T) T&
#define VX_REF(p) (p)
#define VX_ADDR(x) (x)
#define VX_UNUSED(x) ((void)(x))
#define VX_FRAME std::uint32_t*
#define VX_PRECISE
#endif

/* A float is finite when its exponent bits are not all ones (works without isfinite,
 * which fast-math style compilers may fold away). */
#define vx_is_finite(x) ((vx_f_bits(x) & 0x7f800000u) != 0x7f800000u)
#define vx_is_nan(x) ((vx_f_bits(x) & 0x7fffffffu) > 0x7f800000u)

#endif
