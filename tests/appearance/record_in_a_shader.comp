#version 450
// A user's compute shader that traces a ray and evaluates the hit voxel's appearance record
// with the installed includes, and walks the ray front to back with its own trace.
#extension GL_GOOGLE_include_directive : require
#include "voxray/shaders/appearance.glsl"
#include "voxray/shaders/dense_grid.glsl"

layout(local_size_x = 64) in;
layout(push_constant) uniform addresses {
    uvec2 blob, index, records, faces;
    vec4 light;  // xyz towards the light, w ambient
} a;
layout(std430, binding = 0) readonly buffer rays_buffer { vx_ray rays[]; };
layout(std430, binding = 1) writeonly buffer colours_buffer { vec4 colours[]; };
layout(std430, binding = 2) writeonly buffer walked_buffer { vec4 walked[]; };

void main() {
    vx_ray r = rays[gl_GlobalInvocationID.x];
    vx_hit h = vx_dense_grid_trace(vx_words(a.blob), r, VX_MODE_CLOSEST);
    vec4 colour = vec4(0.0);
    if (h.status == VX_STATUS_HIT) {
        uint row = vx_app_row(vx_words(a.index), h.x, h.y, h.z);
        vx_app_light light = vx_app_light(a.light.x, a.light.y, a.light.z, a.light.w);
        if (row != VX_APP_NO_ROW) {
            vx_app_sample s = vx_app_record_sample(vx_words(a.records), vx_words(a.faces), VX_APP_KIND_COMPACT, row,
                                                   r.dx, r.dy, r.dz, light);
            colour = vec4(s.r, s.g, s.b, s.a);
        }
    }
    colours[gl_GlobalInvocationID.x] = colour;

    vx_app_light light = vx_app_light(a.light.x, a.light.y, a.light.z, a.light.w);
    vx_app_walk_cursor c = vx_app_walk_begin(r, vx_app_walk_state_start(), 16u);
    while (c.going != 0u)
        c = vx_app_walk_visit(vx_words(a.index), vx_words(a.records), vx_words(a.faces), VX_APP_KIND_COMPACT, light,
                              1.0e-3, 16u, 0u, vx_dense_grid_trace(vx_words(a.blob), c.r, VX_MODE_CLOSEST), c);
    walked[gl_GlobalInvocationID.x] = vec4(c.s.w.r, c.s.w.g, c.s.w.b, c.s.w.transmittance);
}
