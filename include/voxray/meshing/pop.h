/* The vertex side of POP meshes, one source for the CPU reference (meshing/pop.hpp) and
 * every shader that draws chunk meshes (GLSL, OpenCL C).
 *
 *   rounding     L_i(x) = 2^i floor(x / 2^i) on integer world coordinates: an AND with
 *                ~(2^i - 1), which rounds negative coordinates down as well.
 *   geomorph     L_t(x) = (1 - f) L_i(x) + f L_(i+1)(x), i = floor t, f = t - i.
 *   LOD function t(p) = log2(distance(p, eye)) - bias, clamped to [0, VX_MESH_LEVELS - 1]:
 *                one level coarser each time the distance doubles.
 *   stable t     the fixed point t <- t(L_t(p)) started from the top level, three unrolled
 *                steps, as in the POP-buffer design text.
 *
 * Where t is evaluated: not at the vertex, but at the centre of the cell of the chunk grid
 * that holds the vertex. Per axis a coordinate on a chunk side (a multiple of 64) stays,
 * any other goes to the middle of its chunk: a vertex inside a chunk takes the chunk's
 * centre, one inside a chunk side the side's centre, one on a chunk edge the edge's centre,
 * a chunk corner itself. So
 *   - t is a function of the world position only: a vertex that two chunks share morphs to
 *     the same bits from both;
 *   - t is one value over each cell, and the mesher keeps every merged quad inside one
 *     cell (meshing/mesher.hpp, the border ring): a T-vertex and its host edge morph with
 *     the same t, and a uniform morph keeps it on the edge.
 * The design text starts the fixed point from the largest level of the chunk and its
 * neighbours instead; that start differs between two chunks, so a vertex they share could
 * land in two places. Starting from the top level gives the same answer everywhere.
 *
 * No include guard, like a kernel.h: the host includes it in its own scalar namespace.
 */
#include "voxray/meshing/layout.h"

#define VX_POP_TOP_LEVEL (VX_MESH_LEVELS - 1)

VX_FN vx_i32 vx_pop_round(vx_i32 x, vx_i32 level) { return x & ~((1 << level) - 1); }

VX_FN vx_f32 vx_pop_morph(vx_i32 x, vx_f32 t) {
    vx_f32 lower = vx_floor(t);
    vx_i32 i = vx_f2i(lower);
    vx_f32 a = vx_i2f(vx_pop_round(x, i));
    vx_f32 b = vx_i2f(vx_pop_round(x, i + 1));
    return a + (t - lower) * (b - a);
}

VX_FN vx_f32 vx_pop_lod(vx_f32 x, vx_f32 y, vx_f32 z, vx_f32 eye_x, vx_f32 eye_y, vx_f32 eye_z, vx_f32 bias) {
    vx_f32 dx = x - eye_x, dy = y - eye_y, dz = z - eye_z;
    vx_f32 d2 = vx_fmax(dx * dx + dy * dy + dz * dz, 1.0f);
    vx_f32 t = 0.5f * vx_log2(d2) - bias;
    return vx_fmin(vx_fmax(t, 0.0f), vx_i2f(VX_POP_TOP_LEVEL));
}

/* The centre of the chunk-grid cell that holds coordinate x, per axis. */
VX_FN vx_i32 vx_pop_cell_centre(vx_i32 x) {
    return (x & (VX_MESH_CHUNK_EDGE - 1)) == 0 ? x : (x & ~(VX_MESH_CHUNK_EDGE - 1)) + VX_MESH_CHUNK_EDGE / 2;
}

VX_FN vx_f32 vx_pop_stable_lod(vx_i32 x, vx_i32 y, vx_i32 z, vx_f32 eye_x, vx_f32 eye_y, vx_f32 eye_z, vx_f32 bias) {
    vx_i32 cx = vx_pop_cell_centre(x), cy = vx_pop_cell_centre(y), cz = vx_pop_cell_centre(z);
    vx_f32 t = vx_i2f(VX_POP_TOP_LEVEL);
    t = vx_pop_lod(vx_pop_morph(cx, t), vx_pop_morph(cy, t), vx_pop_morph(cz, t), eye_x, eye_y, eye_z, bias);
    t = vx_pop_lod(vx_pop_morph(cx, t), vx_pop_morph(cy, t), vx_pop_morph(cz, t), eye_x, eye_y, eye_z, bias);
    t = vx_pop_lod(vx_pop_morph(cx, t), vx_pop_morph(cy, t), vx_pop_morph(cz, t), eye_x, eye_y, eye_z, bias);
    return t;
}

/* World integer position of corner c (0..3, layout.h's order) of the quad (w0, w1) of the
 * chunk whose local (0, 0, 0) is at (ox, oy, oz). */
VX_FN void vx_mesh_corner(vx_u32 w0, vx_u32 w1, vx_u32 corner, vx_i32 ox, vx_i32 oy, vx_i32 oz,
                          VX_INOUT(vx_i32) x, VX_INOUT(vx_i32) y, VX_INOUT(vx_i32) z) {
    vx_u32 face = VX_MESH_FACE(w1);
    vx_u32 n = VX_MESH_NORMAL_AXIS(face), u = VX_MESH_U_AXIS(face), v = VX_MESH_V_AXIS(face);
    vx_i32 lift = VX_MESH_POSITIVE(face) ? 1 : 0;
    vx_i32 du = (corner == 1u || corner == 2u) ? vx_u2i(VX_MESH_W(w0)) : 0;
    vx_i32 dv = corner >= 2u ? vx_u2i(VX_MESH_H(w0)) : 0;
    VX_REF(x) = ox + vx_u2i(VX_MESH_X(w0)) + (n == 0u ? lift : 0) + (u == 0u ? du : 0) + (v == 0u ? dv : 0);
    VX_REF(y) = oy + vx_u2i(VX_MESH_Y(w0)) + (n == 1u ? lift : 0) + (u == 1u ? du : 0) + (v == 1u ? dv : 0);
    VX_REF(z) = oz + vx_u2i(VX_MESH_Z(w0)) + (n == 2u ? lift : 0) + (u == 2u ? du : 0) + (v == 2u ? dv : 0);
}

/* The morphed position of world vertex (x, y, z): where a vertex shader puts it. */
VX_FN void vx_pop_vertex(vx_i32 x, vx_i32 y, vx_i32 z, vx_f32 eye_x, vx_f32 eye_y, vx_f32 eye_z, vx_f32 bias,
                         VX_INOUT(vx_f32) px, VX_INOUT(vx_f32) py, VX_INOUT(vx_f32) pz) {
    vx_f32 t = vx_pop_stable_lod(x, y, z, eye_x, eye_y, eye_z, bias);
    VX_REF(px) = vx_pop_morph(x, t);
    VX_REF(py) = vx_pop_morph(y, t);
    VX_REF(pz) = vx_pop_morph(z, t);
}
