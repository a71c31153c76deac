// voxray: appearance records for your own GLSL shaders. Generated from the portable kernels
// that voxray's own backends compile (cmake/voxray_kernels.cmake): do not edit.
//
// Include it right after #version 450 (and your own #extension lines), beside a tracing
// include if you like (the dialect is guarded):
//
//   #version 450
//   #extension GL_GOOGLE_include_directive : require
//   #include "voxray/shaders/appearance.glsl"
//   #include "voxray/shaders/dense_grid.glsl"
//   ...
//   vx_hit h = vx_dense_grid_trace(vx_words(blob_address), r, VX_MODE_CLOSEST);
//   uint row = vx_app_row(vx_words(index_address), h.x, h.y, h.z);      // VX_APP_NO_ROW: none
//   vx_app_sample s = vx_app_record_sample(vx_words(records_address), vx_words(faces_address),
//                                          VX_APP_KIND_COMPACT, row, r.dx, r.dy, r.dz, light);
//
//   index    appearance::ordinal_index(table) words; records: table.words; faces: table.faces
//            (any valid address when the table has none), all by buffer device address
//   kind     VX_APP_KIND_AVERAGES, _COMPACT, _SIX or _SGGX, as the table's record_kind
//   (dx, dy, dz) the unit direction the ray travels; light: vx_app_light { lx, ly, lz, ambient }
//   vx_app_sample { float r, g, b, a, nx, ny, nz; }: linear colour, opacity, normal; blend front to back.
// Or the whole compositing walk with your own trace (appearance/walk_visit.h): up to 16 voxels
// front to back, until less than 1e-3 of the ray is left (no precomputed shadows: 0):
//
//   vx_app_walk_cursor c = vx_app_walk_begin(r, vx_app_walk_state_start(), 16u);
//   while (c.going != 0u)
//       c = vx_app_walk_visit(vx_words(index_address), vx_words(records_address), vx_words(faces_address),
//                             VX_APP_KIND_COMPACT, light, 1.0e-3, 16u, 0u,
//                             vx_dense_grid_trace(vx_words(blob_address), c.r, VX_MODE_CLOSEST), c);
//   c.s.w: vx_app_walk_result { r, g, b, transmittance, t, x, y, z, ... } (pixel_layout.h)
// The values are bit-identical to the C++ backends'. Compile with glslangValidator -V
// --target-env vulkan1.2 -I<voxray prefix>/include.
