#version 450
// A user's vertex shader that pulls POP chunk quads and morphs them with the installed
// include, next to a tracing include (both share the guarded dialect).
#extension GL_GOOGLE_include_directive : require
#include "voxray/shaders/pop.glsl"
#include "voxray/shaders/naadf.glsl"

layout(std430, binding = 0) readonly buffer quads_buffer { uvec2 quads[]; };
layout(push_constant) uniform view {
    mat4 view_projection;
    ivec4 chunk_origin;
    vec4 eye_and_bias;  // xyz eye, w bias
} v;
layout(location = 0) flat out uint material;

void main() {
    const uint corner_of_vertex[6] = uint[6](0u, 1u, 2u, 0u, 2u, 3u);
    uvec2 q = quads[gl_VertexIndex / 6];
    int x, y, z;
    vx_mesh_corner(q.x, q.y, corner_of_vertex[gl_VertexIndex % 6], v.chunk_origin.x, v.chunk_origin.y, v.chunk_origin.z, x, y, z);
    float px, py, pz;
    vx_pop_vertex(x, y, z, v.eye_and_bias.x, v.eye_and_bias.y, v.eye_and_bias.z, v.eye_and_bias.w, px, py, pz);
    gl_Position = v.view_projection * vec4(px, py, pz, 1.0);
    material = VX_MESH_MATERIAL(q.y);
}
