/* Appearance records beside a structure's voxels (issue 25): the table of one record per
 * non-empty voxel, in the order of its voxel ordinal (appearance/table.hpp). Shared by the
 * precompute on the host and the kernels that read records.
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

#endif
