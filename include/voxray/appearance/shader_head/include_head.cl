/* voxray: appearance records for your own OpenCL C 1.2 kernels. Generated from the portable
 * kernels that voxray's own backends compile (cmake/voxray_kernels.cmake): do not edit.
 *
 * Put its text in front of your kernel source (or #include it with -I<voxray prefix>/include),
 * beside a tracing include if you like (the dialect is guarded):
 *
 *   #include "voxray/shaders/appearance.cl"
 *   #include "voxray/shaders/dense_grid.cl"
 *   __kernel void shade(__global const uint* blob, __global const uint* index,
 *                       __global const uint* records, __global const uint* faces, ...) {
 *       vx_hit h = vx_dense_grid_trace(blob, r, VX_MODE_CLOSEST);
 *       uint row = vx_app_row(index, h.x, h.y, h.z);                     // VX_APP_NO_ROW: none
 *       vx_app_sample s = vx_app_record_sample(records, faces, VX_APP_KIND_COMPACT, row,
 *                                              r.dx, r.dy, r.dz, light);
 *   }
 *
 *   index    appearance::ordinal_index(table) words; records: table.words; faces: table.faces
 *   kind     VX_APP_KIND_AVERAGES, _COMPACT, _SIX or _SGGX, as the table's record_kind
 *   (dx, dy, dz) the unit direction the ray travels; light: vx_app_light { lx, ly, lz, ambient }
 *   vx_app_sample { float r, g, b, a, nx, ny, nz; }: linear colour, opacity, normal; blend front to back.
 * Or the whole compositing walk with your own trace (appearance/walk_visit.h): up to 16 voxels
 * front to back, until less than 1e-3 of the ray is left (no precomputed shadows: 0):
 *
 *   vx_app_walk_cursor c = vx_app_walk_begin(r, vx_app_walk_state_start(), 16u);
 *   while (c.going != 0u)
 *       c = vx_app_walk_visit(index, records, faces, VX_APP_KIND_COMPACT, light, 1.0e-3f, 16u, 0u,
 *                             vx_dense_grid_trace(blob, c.r, VX_MODE_CLOSEST), c);
 *   c.s.w: vx_app_walk_result { r, g, b, transmittance, t, x, y, z, ... } (pixel_layout.h)
 * Build with -cl-std=CL1.2 -cl-fp32-correctly-rounded-divide-sqrt: divisions and square roots
 * then round as in C++, which keeps the values bit-identical to the C++ backends'. */
