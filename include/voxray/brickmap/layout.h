/* Byte layout of the brickmap and its address arithmetic, shared by the host type
 * (brickmap/brickmap.hpp, top_grid.hpp, brick_codec.hpp) and the kernel (brickmap/kernel.h).
 * Everything is 32-bit words; offsets are in words from the start of the blob.
 *
 *  blob
 *  +---------------------------+ word 0
 *  | header (32 words)         |  see VX_BM_HEADER_* below
 *  +---------------------------+ header.page_table
 *  | page table                |  one word per page (a 16^3 block of top cells), x fastest:
 *  |                           |  VX_BM_EMPTY_PAGE or the page's index in the page pool
 *  +---------------------------+ header.pages
 *  | page pool                 |  VX_BM_PAGE_WORDS words a page: one top cell per word,
 *  |                           |  index (cx & 15) | (cy & 15) << 4 | (cz & 15) << 8
 *  +---------------------------+ header.bricks
 *  | brick pool                |  header.brick_words words a brick:
 *  |                           |   occupancy: edge^3 bits, voxel bit lx | ly<<b | lz<<2b
 *  |                           |   payload:   edge^3 values of payload_bits each, packed
 *  |                           |              low bits first, same voxel order
 *  +---------------------------+
 *
 *  top cell (32 bits), as in the brickmap paper so that all-zero memory is an empty world:
 *    31                                     1   0
 *   +----------------------------------------+---+
 *   | payload (solid cell) or brick index     | p |   p = 1: brick index in bits 1..31
 *   +----------------------------------------+---+   p = 0: solid cell with payload
 *                                                        bits 1..31; 0 = empty cell
 *
 * The top grid is paged so that a world of 16384^3 voxels (2048^3 top cells with 8^3
 * bricks) costs a 128^3-word page table plus the pages that hold anything.
 */
#ifndef VOXRAY_LAYOUT_BRICKMAP_LAYOUT_H
#define VOXRAY_LAYOUT_BRICKMAP_LAYOUT_H

#define VX_BM_MAGIC 0x4d425856u /* "VXBM" little endian */
#define VX_BM_VERSION 1u

#define VX_BM_HEADER_MAGIC 0
#define VX_BM_HEADER_VERSION 1
#define VX_BM_HEADER_ORIGIN 2        /* 3 words, signed: world position of voxel (0,0,0) */
#define VX_BM_HEADER_EXTENT 5        /* 3 words: world size in voxels */
#define VX_BM_HEADER_CELLS 8         /* 3 words: top grid size in cells */
#define VX_BM_HEADER_PAGES_DIM 11    /* 3 words: page table size in pages */
#define VX_BM_HEADER_BRICK_BITS 14   /* log2 of the brick edge (2..4: edges 4, 8, 16) */
#define VX_BM_HEADER_PAYLOAD_BITS 15 /* 8, 16 or 32 */
#define VX_BM_HEADER_BRICK_WORDS 16  /* words per brick: occupancy + payload */
#define VX_BM_HEADER_OCCUPANCY_WORDS 17
#define VX_BM_HEADER_PAGE_TABLE 18   /* word offsets of the three areas */
#define VX_BM_HEADER_PAGES 19
#define VX_BM_HEADER_BRICKS 20
#define VX_BM_HEADER_PAGE_CAPACITY 21
#define VX_BM_HEADER_BRICK_CAPACITY 22
#define VX_BM_HEADER_WORDS 32

#define VX_BM_PAGE_BITS 4            /* a page is 16^3 top cells */
#define VX_BM_PAGE_EDGE 16
#define VX_BM_PAGE_MASK 15
#define VX_BM_PAGE_WORDS 4096
#define VX_BM_EMPTY_PAGE 0xFFFFFFFFu

#define VX_BM_CELL_EMPTY 0u
#define VX_BM_CELL_IS_BRICK 1u       /* bit 0 */

/* Address arithmetic. Macros, so that one definition serves host integers, GPU integers
 * and SIMD lane vectors alike. (cx, cy, cz) are top cell coordinates. */
#define VX_BM_PAGE_SLOT(cx, cy, cz, pages_x, pages_xy) \
    (((cx) >> VX_BM_PAGE_BITS) + ((cy) >> VX_BM_PAGE_BITS) * (pages_x) + ((cz) >> VX_BM_PAGE_BITS) * (pages_xy))
#define VX_BM_PAGE_CELL(cx, cy, cz) \
    (((cx) & VX_BM_PAGE_MASK) | (((cy) & VX_BM_PAGE_MASK) << 4) | (((cz) & VX_BM_PAGE_MASK) << 8))
/* Index of a voxel inside its brick from its in-brick coordinates (b = log2 edge). */
#define VX_BM_VOXEL_INDEX(lx, ly, lz, b) ((lx) | ((ly) << (b)) | ((lz) << (2 * (b))))
/* Top cell values: a brick index, or a solid cell's payload; either back out of a cell. */
#define VX_BM_BRICK_CELL(index) (((index) << 1) | VX_BM_CELL_IS_BRICK)
#define VX_BM_SOLID_CELL(payload) ((payload) << 1)
#define VX_BM_CELL_VALUE(cell) ((cell) >> 1)

#endif
