#version 450
// Put in front of the flattened portable kernels (cmake/voxray_kernels.cmake) to
// make one GLSL compute shader per structure; backends/vulkan/shaders/entry.glsl follows
// them. The raster shaders (chunk_raster_*.glsl, triangle_raster_*.glsl) start with it
// too. Everything is reached by buffer device address, so no descriptor (and no
// maxStorageBufferRange, 128 MiB on lavapipe) limits the size of a structure.
//
// dialect.glsl (the extensions and the dialect switch) follows; it is also the head of the
// includable sources users put in their own shaders (voxray/shaders/<name>.glsl).
// #line "file" markers (the flattener's), so errors name the original kernel file.
#extension GL_GOOGLE_cpp_style_line_directive : require
