/* The chunk mesh: 8-byte quads in POP order and the table of where each face direction
 * and level of detail starts. Shared by the CPU mesher (meshing/mesher.hpp), the vertex
 * side (meshing/pop.h) and every shader that pulls quads.
 *
 * A chunk is 64^3 voxels at a 64-voxel stride in world integer coordinates (origin =
 * 64 * chunk index, negative indices too). A quad is a rectangle of unit faces of one
 * face direction, one material and one ambient-occlusion pattern, two 32-bit words:
 *
 *  word 0   31 30 29      24 23      18 17      12 11       6 5        0
 *          +-----+----------+----------+----------+----------+----------+
 *          |  0  |  h - 1   |  w - 1   |    z     |    y     |    x     |
 *          +-----+----------+----------+----------+----------+----------+
 *  word 1   31 30 29  27 26  24 23             16 15                      0
 *          +-----+------+------+-----------------+-------------------------+
 *          |  0  |level | face | AO c3 c2 c1 c0  |        material         |
 *          +-----+------+------+-----------------+-------------------------+
 *
 *  x, y, z  the quad's first voxel, chunk-local (0..63). The face lies on that voxel's
 *           side `face` (VX_FACE_*: +X -X +Y -Y +Z -Z), so its plane sits at the voxel's
 *           coordinate along the normal, plus one for a positive face.
 *  w, h     extents in voxels (1..64) along the face's axes u and v:
 *           normal X: u = Y, v = Z;  normal Y: u = Z, v = X;  normal Z: u = X, v = Y.
 *  AO       2 bits per corner, 3 = open, 0 = fully occluded; corners
 *           c0 = (u0,v0), c1 = (u0+w,v0), c2 = (u0+w,v0+h), c3 = (u0,v0+h).
 *  level    how many POP levels the quad survives (1..7): it is drawn at level of
 *           detail i (vertices rounded down to multiples of 2^i) while i < level.
 *
 * The buffer is face-major (face 0 first) and, within a face, coarse to fine (level 7
 * first), so drawing face f at level of detail i draws a prefix of f's quads:
 *
 *  table: VX_MESH_TABLE_ENTRIES words, entry [f * 7 + i] = end of face f's quads drawn at
 *         level i (i = 0..6); face f starts where face f-1's level-0 prefix ends (0 for f = 0).
 *
 *  quads  | face 0: level 7 | 6 | ... | 1 | face 1: 7 | ... | 1 | ... | face 5: ... | 1 |
 *           ^ start(0)       ^ end(0, 6)    ^ end(0, 0) = start(1)
 */
#ifndef VOXRAY_LAYOUT_MESHING_LAYOUT_H
#define VOXRAY_LAYOUT_MESHING_LAYOUT_H

#define VX_MESH_CHUNK_BITS 6
#define VX_MESH_CHUNK_EDGE 64
#define VX_MESH_QUAD_WORDS 2
#define VX_MESH_FACES 6
#define VX_MESH_LEVELS 7        /* levels of detail 0..6: 2^6 = the chunk edge */
#define VX_MESH_MAX_LEVEL 7     /* the most levels a quad survives that are told apart */
#define VX_MESH_TABLE_ENTRIES 42 /* VX_MESH_FACES * VX_MESH_LEVELS */

/* word 0 */
#define VX_MESH_X(w0) ((w0) & 63u)
#define VX_MESH_Y(w0) (((w0) >> 6) & 63u)
#define VX_MESH_Z(w0) (((w0) >> 12) & 63u)
#define VX_MESH_W(w0) ((((w0) >> 18) & 63u) + 1u)
#define VX_MESH_H(w0) ((((w0) >> 24) & 63u) + 1u)
#define VX_MESH_WORD0(x, y, z, w, h) \
    ((x) | ((y) << 6) | ((z) << 12) | (((w) - 1u) << 18) | (((h) - 1u) << 24))

/* word 1 */
#define VX_MESH_MATERIAL(w1) ((w1) & 0xFFFFu)
#define VX_MESH_AO(w1, corner) (((w1) >> (16u + 2u * (corner))) & 3u)
#define VX_MESH_AO_BITS(w1) (((w1) >> 16) & 0xFFu)
#define VX_MESH_FACE(w1) (((w1) >> 24) & 7u)
#define VX_MESH_LEVEL(w1) (((w1) >> 27) & 7u)
#define VX_MESH_WORD1(material, ao_bits, face, level) \
    ((material) | ((ao_bits) << 16) | ((face) << 24) | ((level) << 27))
#define VX_MESH_WITH_LEVEL(w1, level) (((w1) & ~(7u << 27)) | ((level) << 27))
#define VX_MESH_AO_OPEN 0xFFu   /* all four corners 3 */

/* The axes of a face: its normal, and u, v as above. */
#define VX_MESH_NORMAL_AXIS(face) ((face) >> 1)
#define VX_MESH_U_AXIS(face) ((VX_MESH_NORMAL_AXIS(face) + 1u) % 3u)
#define VX_MESH_V_AXIS(face) ((VX_MESH_NORMAL_AXIS(face) + 2u) % 3u)
#define VX_MESH_POSITIVE(face) (((face) & 1u) == 0u)

/* The table: end of face f's quads drawn at level of detail i. */
#define VX_MESH_TABLE_END(f, i) ((f) * VX_MESH_LEVELS + (i))

#endif
