/* voxray: the vertex side of POP chunk meshes for your own OpenCL C 1.2 kernels (a GPU
 * mesher's consumers, software rasterizers). Generated from include/voxray/meshing/pop.h,
 * the source the CPU reference compiles too (cmake/voxray_kernels.cmake): do not edit.
 *
 *   #include "voxray/shaders/pop.cl"
 *   int x, y, z;  vx_mesh_corner(w0, w1, corner, ox, oy, oz, &x, &y, &z);
 *   float px, py, pz;  vx_pop_vertex(x, y, z, eye_x, eye_y, eye_z, bias, &px, &py, &pz);
 */
