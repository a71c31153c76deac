/* voxray: one structure's traversal for your own OpenCL C 1.2 kernels. Generated from the
 * portable kernels that voxray's own backends compile (cmake/voxray_kernels.cmake):
 * do not edit.
 *
 * Put its text in front of your kernel source (or #include it with -I<voxray prefix>/include):
 *
 *   #include "voxray/shaders/brickmap.cl"           // several structures may share a program:
 *   #include "voxray/shaders/naadf.cl"              // the dialect and each kernel are guarded
 *   __kernel void my_kernel(__global const uint* blob, __global const vx_ray* rays, ...) {
 *       vx_hit h = vx_brickmap_trace(blob, rays[get_global_id(0)], VX_MODE_CLOSEST);
 *   }
 *
 * Entry: vx_hit vx_<structure>_trace(__global const uint* blob, vx_ray r, uint mode).
 *   blob    the structure's blob() words exactly as the host has them, in a cl_mem buffer;
 *   vx_ray  { float ox, oy, oz, tmin, dx, dy, dz, tmax; } = voxray::ray (32 bytes);
 *   vx_hit  { float t; int x, y, z; uint face, material, steps, status; } = voxray::hit.
 * Build with -cl-std=CL1.2 -cl-fp32-correctly-rounded-divide-sqrt: 1/d then rounds as in C++,
 * which keeps the hits bit-identical to the C++ backends (t may be -0 where the CPU says +0). */
