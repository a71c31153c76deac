// The GLSL side of the portable dialect: what kernels/prelude.h expects before it. Shared by
// voxray's own shaders (after preamble.glsl) and by the includable voxray/shaders/<name>.glsl.
//
// Addresses travel as uvec2 (low, high word) rather than uint64_t: that needs
// GL_EXT_buffer_reference_uvec2 only, not the shaderInt64 device feature.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
#define VX_DIALECT_GLSL 1
// A writable view of the blob for the commit shader (shaders/commit.glsl, sync/commit.h),
// which copies incremental updates into it. The trace kernels keep the readonly vx_words of
// kernels/prelude.h; declaring this type costs them nothing.
layout(buffer_reference, std430, buffer_reference_align = 4) buffer vx_words_rw { uint w[]; };
