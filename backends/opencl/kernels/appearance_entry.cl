/* voxray OpenCL backend: the compositing walk's entry (appearance/walk.inc), after one
 * structure's kernel, the appearance dialect and the walk instantiated over that kernel's
 * closest hit as vx_app_walk (cmake/voxray_kernels.cmake writes that part). The host looks
 * it up as vx_appearance_walk in program <structure>_appearance (opencl/appearance_walk.hpp).
 * One work-item walks one ray; items past `count` do nothing. Pixels are the 64-byte
 * records of appearance/pixel_layout.h, identical on host and device. */
__kernel void vx_appearance_walk(__global const uint* blob, __global const uint* index,
                                 __global const uint* records, __global const uint* faces,
                                 __global const vx_ray* rays, __global vx_app_walk_result* pixels, uint count,
                                 uint kind, float to_light_x, float to_light_y, float to_light_z, float ambient,
                                 float cutoff, uint max_visits, uint shadows_at) {
    size_t i = get_global_id(0);
    if (i >= count) return;
    vx_app_light light;
    light.lx = to_light_x, light.ly = to_light_y, light.lz = to_light_z, light.ambient = ambient;
    pixels[i] = vx_app_walk(blob, index, records, faces, kind, rays[i], light, cutoff, max_visits, shadows_at,
                            vx_app_walk_state_start()).w;
}
