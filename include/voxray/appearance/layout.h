/* Appearance records beside a structure's voxels (issue 25): the table of one record per
 * non-empty voxel, in the order of its voxel ordinal (appearance/table.hpp). Shared by the
 * precompute on the host and the kernels that read records (appearance/record.h).
 *
 * The *averages* record (the paper's baseline: one colour, one normal, one opacity a voxel),
 * two 32-bit words:
 *
 *  word 0   31        24 23        16 15         8 7          0
 *          +------------+------------+------------+------------+
 *          |  opacity   |     b      |     g      |     r      |
 *          +------------+------------+------------+------------+
 *  word 1   31                      16 15                      0
 *          +--------------------------+--------------------------+
 *          |   normal v (snorm16)     |   normal u (snorm16)     |
 *          +--------------------------+--------------------------+
 *
 *  r, g, b   the mean colour of the surface seen inside the voxel, sRGB-encoded
 *  opacity   the share of the sampling rays through the voxel that hit a surface inside it,
 *            0..255 for 0..1 (the mean over directions)
 *  u, v      the mean normal of the surfaces seen, octahedral (u, v in -1..1); (0, 0) with
 *            opacity 0 when nothing was seen
 *
 * The *compact* record (ours): a 3-word head per voxel, and its faces, 2 words each, in a
 * pool shared by the table (so a voxel pays only for the faces it has):
 *
 *  head 0   31                                                  0
 *          +-----------------------------------------------------+
 *          |        first face: its index in the face pool       |
 *          +-----------------------------------------------------+
 *  head 1   31   28 27   24 23   20 19   16 15   12 11    8 7   4 3    0
 *          +-------+-------+-------+-------+-------+-------+------+------+
 *          |  a5   |  a4   |  a3   |  a2   |  a1   |  a0   |  0   |faces |
 *          +-------+-------+-------+-------+-------+-------+------+------+
 *  head 2   31   28 27   24 23   20 19   16 15   12 11    8 7   4 3    0
 *          +-------+-------+-------+-------+-------+-------+------+------+
 *          |   0   |  a12  |  a11  |  a10  |  a9   |  a8   |  a7  |  a6  |
 *          +-------+-------+-------+-------+-------+-------+------+------+
 *
 *  faces     how many faces follow (0..8): one per octant of the voxel's normal frame that
 *            holds samples (appearance/faces.hpp)
 *  a0..a12   the voxel's opacity along the 13 opacity directions (below), 0..15 for 0..1;
 *            a direction and its opposite see the same silhouette, so 13 cover all 26
 *
 *  face 0   31        24 23        16 15         8 7          0
 *          +------------+------------+------------+------------+
 *          |   weight   |     b      |     g      |     r      |
 *          +------------+------------+------------+------------+
 *  face 1   31        24 23                  12 11                  0
 *          +------------+----------------------+----------------------+
 *          |   spread   |  normal v (snorm12)  |  normal u (snorm12)  |
 *          +------------+----------------------+----------------------+
 *
 *  r, g, b   the face's colour (sRGB-encoded mean of its samples)
 *  weight    the face's share of the voxel's surface (of its samples), 1..255
 *  u, v      the face's mean normal, octahedral
 *  spread    how far its normals stray from the mean: the tangent of the quadrature ring's
 *            angle (record.h), 0..255 for 0..VX_APP_SPREAD_MAX
 *
 * The *six directions* record (the baseline after Crassin et al.'s anisotropic voxels): what
 * the voxel shows to rays travelling along each of the 6 axis directions, lit by one light
 * (so a table is made for a light), one word each, word 2a + (1 if the direction is -a):
 *
 *  word d   31        24 23        16 15         8 7          0
 *          +------------+------------+------------+------------+
 *          |  opacity   |     b      |     g      |     r      |
 *          +------------+------------+------------+------------+
 *          (the bits of the averages record's word 0, read by the same VX_APP_AVG_* macros)
 *
 *  r, g, b   the mean lit colour (sRGB code) of the surfaces that rays of that direction saw
 *            from the front in the voxel
 *  opacity   the share of those rays that stopped, 0..255
 *
 * The *SGGX* record (the baseline after Vicini et al. 2021: an SGGX distribution of normals
 * and their non-exponential transmittance), three words:
 *
 *  word 0   31        24 23        16 15         8 7          0
 *          +------------+------------+------------+------------+
 *          |   gamma    |     b      |     g      |     r      |
 *          +------------+------------+------------+------------+
 *  word 1   31        24 23        16 15         8 7          0
 *          +------------+------------+------------+------------+
 *          |  density   |  sigma z   |  sigma y   |  sigma x   |
 *          +------------+------------+------------+------------+
 *  word 2   31        24 23        16 15         8 7          0
 *          +------------+------------+------------+------------+
 *          |     0      |   r yz     |   r xz     |   r xy     |
 *          +------------+------------+------------+------------+
 *
 *  r, g, b       the mean colour of the samples (sRGB code)
 *  sigma a       sqrt(S_aa), 0..255 for 0..1; r ab = S_ab / (sigma a sigma b), signed 8-bit
 *                (Heitz et al.'s six parameters of the SGGX matrix S)
 *  density       rho, 0..255 for 0..VX_APP_SGGX_DENSITY_MAX: the optical depth along unit w
 *                is rho sqrt(w^T S w) / (|w_x| + |w_y| + |w_z|), the projected area over the
 *                voxel's mean chord
 *  gamma         0..255 for 0..1: T = gamma exp(-tau) + (1 - gamma) max(1 - tau / 2, 0)
 *
 * The *faithful* record (the paper's fields, its section 4: a virtual octahedron of 8 faces
 * with 3 extremal normals and a colour each, and a 3x3x3 subgrid of opacities), 35 words:
 *
 *  word a        31        24 23        16 15         8 7          0      (a = 0, 1, 2)
 *                +------------+------------+------------+------------+
 *                |  scale a   |   e_a z    |   e_a y    |   e_a x    |
 *                +------------+------------+------------+------------+
 *  word 3+3f+k   31        24 23        16 15         8 7          0      (face f = 0..7,
 *                +------------+------------+------------+------------+     vertex k = 0..2)
 *                |  colour k  |   n_k z    |   n_k y    |   n_k x    |
 *                +------------+------------+------------+------------+
 *  word 27..33   the 27 subgrid opacities, element e in byte e % 4 of word 27 + e / 4
 *                (e = x + 3 y + 9 z, the element's place in the voxel); word 33's top byte 0
 *  word 34       31                      16 15          8 7           0
 *                +--------------------------+-------------+-------------+
 *                | normals stored, 2 bits/f |  fixed set  |  has data   |
 *                +--------------------------+-------------+-------------+
 *
 *  e_a       axis a of the SGGX frame of the voxel's normals (snorm8 x, y, z)
 *  scale a   the octahedron's vertex distance along axis a, over the largest, 1..255
 *  face f    the face in octant f of the frame: vertex k lies on axis k, on its negative
 *            side where bit k of f is set
 *  n_k       the face's extremal normal at vertex k (snorm8 x, y, z)
 *  colour k  byte k of the face's colour: r, g, b for k = 0, 1, 2 (sRGB codes)
 *  opacity   hits over rays through the element, 0..255; 0 where no front-facing hit lies
 *  has data  bit f: face f holds samples; fixed set: bit f: its 1..3 normals are stored as
 *            they were seen (not a distribution), how many in bits 16 + 2f
 *
 * The 13 opacity directions: the 3 axes, the 6 face diagonals and the 4 body diagonals of
 * the cube, k = 0..12. Component c of direction k (unnormalised, -1, 0 or 1) is
 * VX_APP_DIR(k, c), a float; its length is 1, sqrt 2 or sqrt 3 as it has 1, 2 or 3 non-zero parts.
 *
 *   k    0  1  2 |  3  4  5  6  7  8 |  9 10 11 12
 *   x    1  0  0 |  1  1  1  1  0  0 |  1  1  1 -1
 *   y    0  1  0 |  1 -1  0  0  1  1 |  1  1 -1  1
 *   z    0  0  1 |  0  0  1 -1  1 -1 |  1 -1  1  1
 */
#ifndef VOXRAY_LAYOUT_APPEARANCE_LAYOUT_H
#define VOXRAY_LAYOUT_APPEARANCE_LAYOUT_H

#define VX_APP_AVERAGES_WORDS 2

#define VX_APP_AVG_R(w0) ((w0) & 0xFFu)
#define VX_APP_AVG_G(w0) (((w0) >> 8) & 0xFFu)
#define VX_APP_AVG_B(w0) (((w0) >> 16) & 0xFFu)
#define VX_APP_AVG_OPACITY(w0) (((w0) >> 24) & 0xFFu)
#define VX_APP_AVG_WORD0(r, g, b, opacity) ((r) | ((g) << 8) | ((b) << 16) | ((opacity) << 24))
#define VX_APP_AVG_NORMAL_U(w1) ((w1) & 0xFFFFu)
#define VX_APP_AVG_NORMAL_V(w1) (((w1) >> 16) & 0xFFFFu)
#define VX_APP_AVG_WORD1(u16, v16) ((u16) | ((v16) << 16))

#define VX_APP_SIX_WORDS 6
#define VX_APP_SGGX_WORDS 3
#define VX_APP_SGGX_DENSITY_MAX 32.0f

#define VX_APP_COMPACT_WORDS 3
#define VX_APP_FACE_WORDS 2
#define VX_APP_MAX_FACES 8
#define VX_APP_DIRECTIONS 13
#define VX_APP_OPACITY_LEVELS 15u
/* The largest spread stored: a ring at atan(2), about 63 degrees from the mean normal. */
#define VX_APP_SPREAD_MAX 2.0f

#define VX_APP_FIRST_FACE(h0) (h0)
#define VX_APP_FACES(h1) ((h1) & 0xFu)
/* The 4-bit opacity of direction k (0..12) from head words 1 and 2. */
#define VX_APP_OPACITY_Q(h1, h2, k) \
    ((k) < 6u ? (((h1) >> (8u + 4u * (k))) & 0xFu) : (((h2) >> (4u * ((k) - 6u))) & 0xFu))

#define VX_APP_FACE_R(f0) ((f0) & 0xFFu)
#define VX_APP_FACE_G(f0) (((f0) >> 8) & 0xFFu)
#define VX_APP_FACE_B(f0) (((f0) >> 16) & 0xFFu)
#define VX_APP_FACE_WEIGHT(f0) (((f0) >> 24) & 0xFFu)
#define VX_APP_FACE_WORD0(r, g, b, weight) ((r) | ((g) << 8) | ((b) << 16) | ((weight) << 24))
#define VX_APP_FACE_NORMAL_U(f1) ((f1) & 0xFFFu)
#define VX_APP_FACE_NORMAL_V(f1) (((f1) >> 12) & 0xFFFu)
#define VX_APP_FACE_SPREAD(f1) (((f1) >> 24) & 0xFFu)
#define VX_APP_FACE_WORD1(u12, v12, spread) ((u12) | ((v12) << 12) | ((spread) << 24))

#define VX_APP_FAITHFUL_WORDS 35
#define VX_APP_FAITHFUL_FACE_WORD(f, k) (3u + 3u * (f) + (k))
#define VX_APP_FAITHFUL_OPACITY_WORD 27u
#define VX_APP_FAITHFUL_FLAGS_WORD 34u
#define VX_APP_FAITHFUL_ELEMENTS 27u
#define VX_APP_FAITHFUL_HAS_DATA(flags, f) (((flags) >> (f)) & 1u)
#define VX_APP_FAITHFUL_FIXED(flags, f) (((flags) >> (8u + (f))) & 1u)
#define VX_APP_FAITHFUL_STORED(flags, f) (((flags) >> (16u + 2u * (f))) & 3u)
/* Byte i (0..3) of word w: the snorm8 components and the top byte of the frame and face words. */
#define VX_APP_BYTE(w, i) (((w) >> (8u * (i))) & 0xFFu)

/* An 8-bit sRGB code's linear value, x = code / 255: a cubic fit of the sRGB curve, within
 * 0.6 %, the same arithmetic on every backend (appearance/record.h, colour_codes.hpp). */
#define VX_APP_SRGB_CUBIC(x) ((x) * ((x) * ((x) * 0.305306011f + 0.682171111f) + 0.012522878f))

/* Direction k's components: bit k of the "non-zero" mask, then of the "negative" mask. */
#define VX_APP_DIR_NONZERO_X 0x1E79u
#define VX_APP_DIR_NONZERO_Y 0x1F9Au
#define VX_APP_DIR_NONZERO_Z 0x1FE4u
#define VX_APP_DIR_NEGATIVE_X 0x1000u
#define VX_APP_DIR_NEGATIVE_Y 0x0810u
#define VX_APP_DIR_NEGATIVE_Z 0x0540u
#define VX_APP_DIR_BIT(mask, k) (((mask) >> (k)) & 1u)
#define VX_APP_DIR_COMPONENT(nonzero, negative, k) \
    (VX_APP_DIR_BIT(nonzero, k) != 0u ? (VX_APP_DIR_BIT(negative, k) != 0u ? -1.0f : 1.0f) : 0.0f)
/* Component c (0, 1, 2 for x, y, z) of direction k, as a float; k and c unsigned. */
#define VX_APP_DIR(k, c)                                                                     \
    ((c) == 0u   ? VX_APP_DIR_COMPONENT(VX_APP_DIR_NONZERO_X, VX_APP_DIR_NEGATIVE_X, k)       \
     : (c) == 1u ? VX_APP_DIR_COMPONENT(VX_APP_DIR_NONZERO_Y, VX_APP_DIR_NEGATIVE_Y, k)       \
                 : VX_APP_DIR_COMPONENT(VX_APP_DIR_NONZERO_Z, VX_APP_DIR_NEGATIVE_Z, k))
/* 1 / length of direction k. */
#define VX_APP_DIR_INV_LENGTH(k) ((k) < 3u ? 1.0f : (k) < 9u ? 0.70710678f : 0.57735027f)

#endif
