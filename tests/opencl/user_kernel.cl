/* A kernel of the user's own that calls voxray's installed traversal (voxray/shaders/<name>.cl,
 * put in front by `#include` through -I<include dir>): per ray, the closest hit and, from a
 * second call, whether anything blocks the ray. USER_TRACE names the structure's entry. */
__kernel void user_trace(__global const uint* blob, __global const vx_ray* rays, __global vx_hit* hits,
                         __global uint* blocked, uint count) {
    size_t i = get_global_id(0);
    if (i >= count) return;
    vx_ray r = rays[i];
    hits[i] = USER_TRACE(blob, r, VX_MODE_CLOSEST);
    blocked[i] = USER_TRACE(blob, r, VX_MODE_ANY).status == VX_STATUS_HIT ? 1u : 0u;
}
