/* A user's OpenCL C kernel that traces a ray and evaluates the hit voxel's appearance record
 * with the installed includes, and walks the ray front to back with its own trace. */
#include "voxray/shaders/appearance.cl"
#include "voxray/shaders/dense_grid.cl"

__kernel void shade(__global const uint* blob, __global const uint* index, __global const uint* records,
                    __global const uint* faces, __global const vx_ray* rays, float4 to_light, __global float4* out) {
    vx_ray r = rays[get_global_id(0)];
    vx_hit h = vx_dense_grid_trace(blob, r, VX_MODE_CLOSEST);
    float4 colour = (float4)(0.0f);
    if (h.status == VX_STATUS_HIT) {
        uint row = vx_app_row(index, h.x, h.y, h.z);
        vx_app_light light;
        light.lx = to_light.x, light.ly = to_light.y, light.lz = to_light.z, light.ambient = to_light.w;
        if (row != VX_APP_NO_ROW) {
            vx_app_sample s = vx_app_record_sample(records, faces, VX_APP_KIND_COMPACT, row, r.dx, r.dy, r.dz, light);
            colour = (float4)(s.r, s.g, s.b, s.a);
        }
    }
    out[get_global_id(0)] = colour;
}

__kernel void walk(__global const uint* blob, __global const uint* index, __global const uint* records,
                   __global const uint* faces, __global const vx_ray* rays, float4 to_light, __global float4* out) {
    vx_app_light light;
    light.lx = to_light.x, light.ly = to_light.y, light.lz = to_light.z, light.ambient = to_light.w;
    vx_app_walk_cursor c = vx_app_walk_begin(rays[get_global_id(0)], vx_app_walk_state_start(), 16u);
    while (c.going != 0u)
        c = vx_app_walk_visit(index, records, faces, VX_APP_KIND_COMPACT, light, 1.0e-3f, 16u, 0u,
                              vx_dense_grid_trace(blob, c.r, VX_MODE_CLOSEST), c);
    out[get_global_id(0)] = (float4)(c.s.w.r, c.s.w.g, c.s.w.b, c.s.w.transmittance);
}
