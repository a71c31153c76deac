// voxray: one structure's traversal for your own GLSL shaders. Generated from the portable
// kernels that voxray's own backends compile (cmake/voxray_kernels.cmake): do not edit.
//
// Include it right after #version 450 (and your own #extension lines), before any declaration:
//
//   #version 450
//   #extension GL_GOOGLE_include_directive : require
//   #include "voxray/shaders/brickmap.glsl"        // several structures may share a shader:
//   #include "voxray/shaders/naadf.glsl"           // the dialect and each kernel are guarded
//   ...
//   vx_hit h = vx_brickmap_trace(vx_words(blob_address), r, VX_MODE_CLOSEST);  // or VX_MODE_ANY
//
// Entry: vx_hit vx_<structure>_trace(vx_words blob, vx_ray r, uint mode), one ray per call.
//   blob   the structure's blob() words exactly as the host has them, in a buffer the shader
//          reaches by device address: vx_words(uvec2(low, high)) (Vulkan 1.2 bufferDeviceAddress).
//   vx_ray { float ox, oy, oz, tmin, dx, dy, dz, tmax; }  = voxray::ray (32 bytes, std430)
//   vx_hit { float t; int x, y, z; uint face, material, steps, status; }  = voxray::hit;
//          status VX_STATUS_HIT or VX_STATUS_MISS; face VX_FACE_* (core/ray_hit_layout.h).
// The hits are bit-identical to the C++ backends' (t may be -0 where the CPU says +0).
// Compile with glslangValidator -V --target-env vulkan1.2 -I<voxray prefix>/include.
