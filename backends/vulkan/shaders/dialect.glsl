// The GLSL side of the portable dialect: what kernels/prelude.h expects before it. Shared by
// voxray's own shaders (after preamble.glsl) and by the includable voxray/shaders/<name>.glsl.
//
// Addresses travel as uvec2 (low, high word) rather than uint64_t: that needs
// GL_EXT_buffer_reference_uvec2 only, not the shaderInt64 device feature.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#define VX_DIALECT_GLSL 1
// The frame passes (world/frame/passes.h) pack their visibility buffer into 64-bit words and keep
// the nearest hit by atomicMax: only their shader asks for int64 (shaderInt64 and
// shaderBufferInt64Atomics, which the engine checks before it builds that pipeline).
#ifdef VX_INT64_ATOMICS
#extension GL_EXT_shader_explicit_arithmetic_types_int64 : require
#extension GL_EXT_shader_atomic_int64 : require
#endif
// A writable view of the blob for the commit shader (shaders/commit.glsl, sync/commit.h),
// which copies incremental updates into it. The trace kernels keep the readonly vx_words of
// kernels/prelude.h; declaring this type costs them nothing.
layout(buffer_reference, std430, buffer_reference_align = 4) buffer vx_words_rw { uint w[]; };
#ifdef VX_INT64_ATOMICS
layout(buffer_reference, std430, buffer_reference_align = 8) buffer vx_words64 { uint64_t w[]; };
#endif
