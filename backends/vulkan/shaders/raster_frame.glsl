// What the raster shaders (chunk_raster_*.glsl, triangle_raster_*.glsl) share: the push
// constants of one frame and the colour buffer. Must match voxray::vulkan_detail::raster_push
// (voxray/vulkan/raster_pipeline.hpp), 128 bytes: the least every device offers.
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer vx_raster_colours { uint c[]; };

// frame.fixed_level when the level of detail follows the distance (meshing/pop.h).
#define VX_RASTER_BY_DISTANCE 0xFFFFFFFFu

layout(push_constant, std430) uniform vx_raster_push {
    mat4 view_projection;  // from eye-relative world coordinates to clip space
    vec4 eye_and_bias;     // xyz: the eye; w: the LOD bias of meshing/pop.h
    vec4 sun;              // xyz: towards the sun (unit length)
    // Buffers by device address. Chunks: quads, origins (ivec4 a chunk), colours (RGBA8 a
    // material). Triangles: positions (3 floats a vertex), indices (3 a triangle), colour.
    uvec2 data[3];
    uint colour_count;
    uint fixed_level;      // every chunk drawn at this level, or VX_RASTER_BY_DISTANCE
} frame;

// The palette colour lit like voxray::shade (rays/shading.hpp) without shadows,
// gamma-encoded like voxray::to_srgb8.
vec4 vx_raster_shade(uint material, vec3 normal) {
    uint c = material < frame.colour_count ? vx_raster_colours(frame.data[2]).c[material] : 0xFFFF00FFu;
    vec3 albedo = vec3(float(c & 255u), float((c >> 8) & 255u), float((c >> 16) & 255u)) / 255.0;
    float lambert = max(0.0, dot(normal, frame.sun.xyz));
    return vec4(pow(albedo * (0.3 + 0.7 * lambert), vec3(1.0 / 2.2)), 1.0);
}
