// What the chunk raster shaders (chunk_raster_vert.glsl, chunk_raster_frag.glsl) share: the
// buffers they reach by device address and the push constants of one frame. Must match
// voxray::vulkan_detail::raster_push (voxray/vulkan/raster_pipeline.hpp), 128 bytes: the
// least every device offers.
layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer vx_raster_quads { uvec2 q[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer vx_raster_origins { ivec4 o[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer vx_raster_colours { uint c[]; };

layout(push_constant, std430) uniform vx_raster_push {
    mat4 view_projection;  // from eye-relative world coordinates to clip space
    vec4 eye_and_bias;     // xyz: the eye; w: the LOD bias of meshing/pop.h
    vec4 sun;              // xyz: towards the sun (unit length)
    uvec2 quads;           // every chunk's quads, one after another (meshing/layout.h)
    uvec2 origins;         // ivec4 per chunk: its world origin; indexed by gl_InstanceIndex
    uvec2 colours;         // RGBA8 per material
    uint colour_count;
    uint unused;
} frame;
