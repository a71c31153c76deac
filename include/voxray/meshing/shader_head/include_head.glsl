// voxray: the vertex side of POP chunk meshes for your own GLSL shaders. Generated from
// include/voxray/meshing/pop.h, the source the CPU reference compiles too
// (cmake/voxray_kernels.cmake): do not edit.
//
// Include it right after #version 450 (and your own #extension lines), before any declaration:
//
//   #version 450
//   #extension GL_GOOGLE_include_directive : require
//   #include "voxray/shaders/pop.glsl"      // may share a shader with the tracing includes
//
// Per vertex (vertex pulling, 6 vertices a quad, no vertex buffer):
//   uvec2 q = quads[gl_VertexIndex / 6];                    // a chunk mesh's words (layout.h)
//   int x, y, z;  vx_mesh_corner(q.x, q.y, corner, chunk_origin.x, chunk_origin.y, chunk_origin.z, x, y, z);
//   float px, py, pz;  vx_pop_vertex(x, y, z, eye.x, eye.y, eye.z, lod_bias, px, py, pz);
//   gl_Position = view_projection * vec4(px, py, pz, 1.0);
// Draw face f of a chunk at level of detail L: quads [face_begin(f), face_end(f, L)) of the
// buffer, L from chunk_draw_level() on the host (meshing/pop.hpp). Compile with
// glslangValidator -V --target-env vulkan1.2 -I<voxray prefix>/include.
