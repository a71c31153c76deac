#version 450
// Put in front of the flattened portable kernels (scripts/cmake/voxray_kernels.cmake) to
// make one GLSL compute shader per structure; backends/vulkan/shaders/entry.glsl follows
// them. Everything is reached by buffer device address, so no descriptor (and no
// maxStorageBufferRange, 128 MiB on lavapipe) limits the size of a structure.
//
// Addresses travel as uvec2 (low, high word) rather than uint64_t: that needs
// GL_EXT_buffer_reference_uvec2 only, not the shaderInt64 device feature.
#extension GL_EXT_buffer_reference : require
#extension GL_EXT_buffer_reference_uvec2 : require
// #line "file" markers (the flattener's), so errors name the original kernel file.
#extension GL_GOOGLE_cpp_style_line_directive : require
#define VX_DIALECT_GLSL 1
// A writable view of the blob for the commit shader (shaders/commit.glsl, sync/commit.h),
// which copies incremental updates into it. The trace kernels keep the readonly vx_words of
// kernels/prelude.h; declaring this type costs them nothing.
layout(buffer_reference, std430, buffer_reference_align = 4) buffer vx_words_rw { uint w[]; };
