/* The ordinal index's layout (issue 25): from a voxel to its row in an appearance table, for any
 * structure, since every first-hit kernel returns the voxel it hit. Rows follow the index's
 * order: bricks of 4^3 voxels in (z, y, x) order, and inside a brick its voxels in (z, y, x)
 * order (appearance/table.hpp sorts by the same rule). A voxel's row is its brick's first
 * row plus the occupied voxels before it in the brick: one popcount or two.
 *
 *   word   0..2   origin: the min voxel of brick (0, 0, 0), a multiple of 4 on each axis
 *          3..5   bricks along x, y, z
 *          6      word of the first brick record
 *          7      0
 *          8..    brick table, (z, y, x) order: a brick's record number, or VX_APP_NO_BRICK
 *   record        3 words: the brick's first row, then its occupancy, voxel bit
 *                 (x & 3) | (y & 3) << 2 | (z & 3) << 4, bits 0..31 then 32..63
 *
 *   occupancy  word 1 of a record             word 2 of a record
 *             31                       0     31                       0
 *            +--------------------------+   +--------------------------+
 *            | voxels z = 0..1 of brick |   | voxels z = 2..3 of brick |
 *            +--------------------------+   +--------------------------+
 *
 * The lookup is vx_app_row (appearance/ordinal.h); the host builds the index in
 * appearance/ordinal_index.hpp. */
#ifndef VOXRAY_LAYOUT_APPEARANCE_ORDINAL_LAYOUT_H
#define VOXRAY_LAYOUT_APPEARANCE_ORDINAL_LAYOUT_H

#define VX_APP_ORD_HEADER_WORDS 8u
#define VX_APP_ORD_RECORD_WORDS 3u
#define VX_APP_NO_BRICK 0xFFFFFFFFu
#define VX_APP_NO_ROW 0xFFFFFFFFu
/* A voxel's bit in its brick, from its coordinates relative to the origin (ints). */
#define VX_APP_BRICK_BIT(x, y, z) (((x) & 3) | (((y) & 3) << 2) | (((z) & 3) << 4))

#endif
