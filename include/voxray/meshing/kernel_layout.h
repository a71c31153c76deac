/* The mesher kernel's buffers (meshing/kernel.h): the chunks it reads and the words it
 * writes. Shared by the kernel and the host that packs and unpacks them
 * (meshing/kernel_words.hpp), on every backend.
 *
 * Input, VX_MK_CHUNK_WORDS words per chunk, chunk c at c * VX_MK_CHUNK_WORDS:
 *
 *   word 0            8712             8849             8986                      74522
 *        +----------------+----------------+----------------+--------------------------+
 *        | occupancy rows | x shell, low   | x shell, high  | materials, 4 bytes/word  |
 *        +----------------+----------------+----------------+--------------------------+
 *
 *   rows       row (y, z), y and z in -1..64, at 2 * ((z + 1) * 66 + (y + 1)): bits x = 0..31
 *              in its first word, x = 32..63 in its second (meshing/chunk.hpp's rows)
 *   x shell    bit (z + 1) * 66 + (y + 1) set where voxel (-1, y, z) (low) or (64, y, z)
 *              (high) is solid; bit i lives in word i / 32, at i % 32
 *   materials  voxel (x, y, z) of the chunk at index x + 64 (y + 64 z): byte i % 4 (low
 *              byte first) of word i / 4; 0 = empty
 *
 * Output, the frame: a header, then one block of VX_MK_BLOCK_WORDS(capacity) per chunk.
 *
 *   header  [0] chunks  [1] flags (VX_MK_FLAG_*)  [2] capacity: the most quads a block holds
 *           [3] unused
 *
 *   block   0                  3072        3114   3115   3116
 *           +------------------+-------------+------+------+------------------------------+
 *           | per plane, 8     | table       |total |unused| quads, 2 words each,         |
 *           | counters         | (layout.h)  |      |      | `capacity` of them            |
 *           +------------------+-------------+------+------+------------------------------+
 *
 *   plane   face * 64 + layer (the layer along the face's normal); its 8 counters, [level]
 *           for levels 1..7 ([0] unused): first how many quads of that level the plane has
 *           (pass count), then where they go (pass place; pass emit advances them).
 *   total   the chunk's quads. Over `capacity` the emit pass writes none of them, and the
 *           host reports the numbers.
 */
#ifndef VOXRAY_LAYOUT_MESHING_KERNEL_LAYOUT_H
#define VOXRAY_LAYOUT_MESHING_KERNEL_LAYOUT_H

#include "voxray/meshing/layout.h"

#define VX_MK_PADDED 66u
#define VX_MK_ROWS 0u
#define VX_MK_X_LOW (2u * VX_MK_PADDED * VX_MK_PADDED)
#define VX_MK_SHELL_WORDS ((VX_MK_PADDED * VX_MK_PADDED + 31u) / 32u)
#define VX_MK_X_HIGH (VX_MK_X_LOW + VX_MK_SHELL_WORDS)
#define VX_MK_MATERIALS (VX_MK_X_HIGH + VX_MK_SHELL_WORDS)
#define VX_MK_CHUNK_WORDS (VX_MK_MATERIALS + 64u * 64u * 64u / 4u)

/* Row (y, z) and shell bit (y, z), y and z in -1..64. */
#define VX_MK_ROW(y, z) (((z) + 1) * 66 + ((y) + 1))

#define VX_MK_FLAG_AO 1u   /* ambient occlusion: 4 x 2 bits per quad, merging stops where it differs */
#define VX_MK_FLAG_POP 2u  /* POP order; without it every quad has level 7 (in every prefix) */

#define VX_MK_HEADER_CHUNKS 0u
#define VX_MK_HEADER_FLAGS 1u
#define VX_MK_HEADER_CAPACITY 2u
#define VX_MK_HEADER_WORDS 4u

#define VX_MK_PLANES (VX_MESH_FACES * 64u)
#define VX_MK_COUNTERS 8u
#define VX_MK_TABLE (VX_MK_PLANES * VX_MK_COUNTERS)
#define VX_MK_TOTAL (VX_MK_TABLE + VX_MESH_TABLE_ENTRIES)
#define VX_MK_QUADS (VX_MK_TOTAL + 2u)
#define VX_MK_BLOCK_WORDS(capacity) (VX_MK_QUADS + (capacity) * VX_MESH_QUAD_WORDS)

/* The passes, run in this order, each to completion: items per chunk. */
#define VX_MK_PASS_COUNT 0u  /* VX_MK_PLANES items a chunk: count each plane's quads per level */
#define VX_MK_PASS_PLACE 1u  /* 1 item a chunk: counts -> starts, the table and the total */
#define VX_MK_PASS_EMIT 2u   /* VX_MK_PLANES items a chunk: the quads, at their starts */

#endif
