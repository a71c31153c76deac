/* Kernel-side ray and hit: per-lane fields in the order of core/ray_hit_layout.h, so
 * with scalar lanes (GPU dialects) they are exactly the records in the ray/hit buffers.
 * Included once per lane set; no include guard on purpose (see cpu/lanes.hpp). */
VX_STRUCT(vx_ray)
    vx_f32 ox, oy, oz, tmin;
    vx_f32 dx, dy, dz, tmax;
VX_END_STRUCT(vx_ray)

VX_STRUCT(vx_hit)
    vx_f32 t;
    vx_i32 x, y, z;
    vx_u32 face;
    vx_u32 material;
    vx_u32 steps;
    vx_u32 status;
VX_END_STRUCT(vx_hit)
