/* Word layout of the chunked world and its index arithmetic, shared by the host packer
 * (world/world_blob.hpp) and the kernel (world/kernel.h) in every dialect. 32-bit words;
 * every offset is in words from the start of the blob.
 *
 * The world is a grid of cells, each the region of one LOD 0 chunk (C = 2^chunk_bits
 * voxels a side). A chunk of LOD n is a DAG of the same C^3 resolution over 2^n x 2^n x 2^n
 * cells (a DAG voxel is 2^n world voxels a side). What the rays see is a cut through the
 * LOD octree: every cell is traced through the one chunk, of any LOD, that stands for it.
 *
 *  blob
 *  +-------------------------------+ word 0
 *  | header (20 words)             |  magic 'VXWD', version, origin, extent, shift (xyz
 *  |                               |  each), chunk_bits, root level, root, attribute kind,
 *  |                               |  chunk table offset and rows
 *  +-------------------------------+ header.root
 *  | directory: an octree over the |  nodes of 8 child words; entries of 4 words
 *  | cells, its leaves the entries |
 *  +-------------------------------+ header.table
 *  | chunk table: one row of 8     |  the entries as a flat list, with their boxes, for
 *  | words per entry               |  the frame passes (world/frame/passes.h)
 *  +-------------------------------+
 *  | chunk DAGs (svdag/layout.h)   |  each a whole svdag blob, header included, whose
 *  |                               |  pointers are relative to its own header: a chunk's
 *  |                               |  words are the same wherever it is placed
 *  +-------------------------------+
 *
 *  directory node at level L (a region of 2^L cells a side): 8 child words, by octant
 *  x | y << 1 | z << 2 of the child regions (level L - 1):
 *      0                  the child region has no voxels (a ray leaves it in one move)
 *      w, bit 0 clear     the child is a node, at word w
 *      w | 1              the child is an entry, at word w
 *  The root is at level header.root_level, its region the grid's first 2^root_level cells.
 *
 *  entry (for a region of level r): the chunk that stands for the region's cells, 4 words:
 *   word 0   its DAG: word offset of the DAG's header
 *   word 1   its LOD n >= r (n > r: a part of a coarser chunk, finer ones stand for other
 *            parts of it; a walk in it goes back to the directory when it leaves the region)
 *   word 2   solid box min: x | y << 10 | z << 20, in the chunk's DAG voxels [0, C)
 *   word 3   solid box max, inclusive, packed alike
 *
 *      bits  31 30 | 29 ......... 20 | 19 ......... 10 | 9 .......... 0
 *             0  0 |        z        |        y        |       x
 *
 *  chunk table row (8 words): an entry and its solid box in walk voxels, which the frame
 *  passes cull and draw chunk by chunk (a coarse chunk split around finer ones keeps its
 *  whole box: the walk restricted to its entry skips the finer chunks' regions):
 *   word 0   the entry's child word (entry offset | VX_WD_CHILD_IS_ENTRY)
 *   word 1-3 box min x, y, z (walk voxels, signed)
 *   word 4-6 box max x, y, z, exclusive
 *   word 7   the chunk's LOD
 *
 * Coordinates: walk voxel (0,0,0) is the world's min corner (world position `origin`,
 * where the reference walk starts too, so every t is computed from the same numbers);
 * walk + shift is the grid coordinate, whose cell (0,0,0) starts at a multiple of
 * C * 2^root_level, so every region of every LOD is aligned: a LOD n chunk's DAG
 * coordinates are (grid >> n), its octant bits below bit chunk_bits. */
#ifndef VOXRAY_LAYOUT_WORLD_LAYOUT_H
#define VOXRAY_LAYOUT_WORLD_LAYOUT_H

#define VX_WD_MAGIC 0x44575856u /* "VXWD" little endian */
#define VX_WD_VERSION 2u

#define VX_WD_HEADER_MAGIC 0
#define VX_WD_HEADER_VERSION 1
#define VX_WD_HEADER_ORIGIN 2        /* 3 words, signed: world position of walk voxel (0,0,0) */
#define VX_WD_HEADER_EXTENT 5        /* 3 words: the world's size in voxels */
#define VX_WD_HEADER_SHIFT 8         /* 3 words: grid coordinate of walk voxel (0,0,0) */
#define VX_WD_HEADER_CHUNK_BITS 11   /* C = 2^chunk_bits */
#define VX_WD_HEADER_ROOT_LEVEL 12   /* the root node's region is 2^root_level cells a side */
#define VX_WD_HEADER_ROOT 13         /* word offset of the root node */
#define VX_WD_HEADER_ATTRIBUTE_KIND 14 /* VX_SV_ATTRIBUTES_*, the same in every chunk */
#define VX_WD_HEADER_TABLE 15        /* word offset of the chunk table */
#define VX_WD_HEADER_TABLE_ROWS 16   /* its rows: one per entry */
#define VX_WD_HEADER_WORDS 20

#define VX_WD_NODE_WORDS 8
#define VX_WD_CHILD_IS_ENTRY 1u
#define VX_WD_ENTRY_WORDS 4
#define VX_WD_ENTRY_DAG 0
#define VX_WD_ENTRY_LOD 1
#define VX_WD_ENTRY_BOX_MIN 2
#define VX_WD_ENTRY_BOX_MAX 3

#define VX_WD_ROW_WORDS 8
#define VX_WD_ROW_ENTRY 0
#define VX_WD_ROW_MIN 1
#define VX_WD_ROW_MAX 4
#define VX_WD_ROW_LOD 7

#define VX_WD_MIN_CHUNK_BITS 4       /* a chunk holds whole 16^3 model chunks */
#define VX_WD_MAX_CHUNK_BITS 10      /* box coordinates are 10 bits */
#define VX_WD_MAX_LOD 20

#define VX_WD_BOX_PACK(x, y, z) ((x) | ((y) << 10) | ((z) << 20))
#define VX_WD_BOX_X(w) ((w) & 1023u)
#define VX_WD_BOX_Y(w) (((w) >> 10) & 1023u)
#define VX_WD_BOX_Z(w) (((w) >> 20) & 1023u)

#endif
