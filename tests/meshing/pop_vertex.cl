/* A user's OpenCL C kernel that morphs POP chunk quads with the installed include. */
#include "voxray/shaders/pop.cl"

__kernel void morph_corners(__global const uint* quads, int ox, int oy, int oz, float ex, float ey, float ez, float bias,
                            __global float* out) {
    uint i = get_global_id(0);
    int x, y, z;
    vx_mesh_corner(quads[2 * (i / 4)], quads[2 * (i / 4) + 1], i % 4, ox, oy, oz, &x, &y, &z);
    float px, py, pz;
    vx_pop_vertex(x, y, z, ex, ey, ez, bias, &px, &py, &pz);
    out[3 * i] = px, out[3 * i + 1] = py, out[3 * i + 2] = pz;
}
