/* Byte layout of NAADF (nested cells with axis-aligned distance fields) and its address
 * arithmetic, shared by the host builder (naadf/naadf.hpp, naadf/builder.hpp) and the
 * kernel (naadf/kernel.h). Everything is 32-bit words; offsets are in words.
 *
 * Four layers of cells, each a grid of the layer below:
 *   page   256^3 voxels = 16^3 chunks   (the sparse top level: a dense table of pages)
 *   chunk   16^3 voxels =  4^3 blocks
 *   block    4^3 voxels
 *   voxel
 * The paper has chunk, block and voxel over a dense chunk grid (4 GB at 16384^3); the page
 * table above the chunks makes the top level sparse (a 16384^3 world: 64^3 pages, 1 MiB)
 * while an empty page skips as fast as an empty chunk does: it is a cell with an AADF too.
 *
 *  blob
 *  +---------------------------+ word 0
 *  | header (32 words)         |  VX_NA_HEADER_* below
 *  +---------------------------+ header.page_table
 *  | page table                |  one cell word per page, x fastest
 *  +---------------------------+ header.chunks
 *  | chunk arrays              |  4096 cell words per mixed page, index VX_NA_CHUNK_INDEX
 *  +---------------------------+ header.blocks
 *  | block arrays              |  64 cell words per mixed chunk, index VX_NA_BLOCK_INDEX
 *  +---------------------------+ header.voxels
 *  | voxel groups              |  32 words per group of 4^3 voxels (16 bits each, voxel i
 *  |                           |  in word i >> 1 at bit 16 * (i & 1)); groups are shared
 *  +---------------------------+  by every block with the same 64 voxels (hashed)
 *
 *  cell word (page, chunk or block), 32 bits:
 *    31 30 29                                                   0
 *   +-----+------------------------------------------------------+
 *   | 0 0 | AADF: six fields of k bits, +x -x +y -y +z -z,       |  empty
 *   |     | +x lowest (k = 5 for pages and chunks, 2 for blocks) |
 *   +-----+------------------------------------------------------+
 *   | 0 1 | type (15 bits, in bits 0..14)                        |  uniform: every voxel solid,
 *   +-----+------------------------------------------------------+  one type
 *   | 1 0 | index of the child array (chunk array, block array,  |  mixed
 *   |     | or voxel group), in arrays, not words                |
 *   +-----+------------------------------------------------------+
 *  All-zero memory is empty space with AADF 0, which is always correct.
 *
 *  voxel, 16 bits:
 *    15  14      12 11                             0
 *   +---+----------+-------------------------------+
 *   | 0 |    0     | AADF: six 2-bit fields (above) |  empty
 *   +---+----------+-------------------------------+
 *   | 1 |        type (15 bits)                     |  solid
 *   +---+-------------------------------------------+
 *
 * An AADF field is how many cells of the same layer the empty cuboid around the cell
 * reaches in that direction; it stays inside the cell of the layer above (a voxel's inside
 * its block, a block's inside its chunk, a chunk's inside its page), so it depends only on
 * that cell's content and deduplicated groups stay valid. Pages reach up to 31 pages.
 *
 * Coordinates: the kernel walks in voxels relative to the world's min corner (header.origin);
 * the cell grid is aligned to multiples of 256 in world coordinates, so grid coordinate
 * g = p + header.shift (0 <= shift < 256) and model chunks map to chunks one to one.
 */
#ifndef VOXRAY_NAADF_LAYOUT_H
#define VOXRAY_NAADF_LAYOUT_H

#define VX_NA_MAGIC 0x46414e56u /* "VNAF" little endian */
#define VX_NA_VERSION 1u

#define VX_NA_HEADER_MAGIC 0
#define VX_NA_HEADER_VERSION 1
#define VX_NA_HEADER_ORIGIN 2      /* 3 words, signed: world position of voxel (0,0,0) */
#define VX_NA_HEADER_EXTENT 5      /* 3 words: world size in voxels */
#define VX_NA_HEADER_SHIFT 8       /* 3 words: grid coordinate of voxel (0,0,0) */
#define VX_NA_HEADER_PAGES_DIM 11  /* 3 words: page table size in pages */
#define VX_NA_HEADER_PAGE_TABLE 14 /* word offsets of the four areas */
#define VX_NA_HEADER_CHUNKS 15
#define VX_NA_HEADER_BLOCKS 16
#define VX_NA_HEADER_VOXELS 17
#define VX_NA_HEADER_CHUNK_ARRAYS 18 /* counts of the arrays in each area */
#define VX_NA_HEADER_BLOCK_ARRAYS 19
#define VX_NA_HEADER_GROUPS 20
#define VX_NA_HEADER_WORDS 32

/* Layers: log2 of a cell's edge in voxels, and bits per AADF field. */
#define VX_NA_PAGE_BITS 8
#define VX_NA_CHUNK_BITS 4
#define VX_NA_BLOCK_BITS 2
#define VX_NA_PAGE_AADF_BITS 5
#define VX_NA_CHUNK_AADF_BITS 5
#define VX_NA_BLOCK_AADF_BITS 2
#define VX_NA_VOXEL_AADF_BITS 2
#define VX_NA_CHUNK_ARRAY_WORDS 4096 /* chunks of a page */
#define VX_NA_BLOCK_ARRAY_WORDS 64   /* blocks of a chunk */
#define VX_NA_GROUP_WORDS 32         /* 64 voxels of 16 bits */

#define VX_NA_EMPTY 0u
#define VX_NA_UNIFORM 1u
#define VX_NA_MIXED 2u
#define VX_NA_STATE(cell) ((cell) >> 30)
#define VX_NA_PAYLOAD(cell) ((cell) & 0x3FFFFFFFu)
#define VX_NA_TYPE_MASK 0x7FFFu
#define VX_NA_UNIFORM_CELL(type) ((VX_NA_UNIFORM << 30) | (type))
#define VX_NA_MIXED_CELL(index) ((VX_NA_MIXED << 30) | (index))
#define VX_NA_MAX_INDEX 0x3FFFFFFFu
#define VX_NA_VOXEL_SOLID 0x8000u
#define VX_NA_SOLID_VOXEL(type) (VX_NA_VOXEL_SOLID | (type))

/* AADF field `dir` (0..5: +x -x +y -y +z -z) of k bits each, and packing one field. */
#define VX_NA_AADF_FIELD(aadf, dir, k) (((aadf) >> ((dir) * (k))) & ((1u << (k)) - 1u))
#define VX_NA_AADF_PUT(dist, dir, k) ((dist) << ((dir) * (k)))

/* Address arithmetic on grid coordinates (gx, gy, gz). Macros, so that one definition
 * serves host integers, GPU integers and SIMD lane vectors alike. */
#define VX_NA_PAGE_SLOT(gx, gy, gz, pages_x, pages_xy) \
    (((gx) >> VX_NA_PAGE_BITS) + ((gy) >> VX_NA_PAGE_BITS) * (pages_x) + ((gz) >> VX_NA_PAGE_BITS) * (pages_xy))
#define VX_NA_CHUNK_INDEX(gx, gy, gz) \
    ((((gx) >> 4) & 15) | ((((gy) >> 4) & 15) << 4) | ((((gz) >> 4) & 15) << 8))
#define VX_NA_BLOCK_INDEX(gx, gy, gz) ((((gx) >> 2) & 3) | ((((gy) >> 2) & 3) << 2) | ((((gz) >> 2) & 3) << 4))
#define VX_NA_VOXEL_INDEX(gx, gy, gz) (((gx) & 3) | (((gy) & 3) << 2) | (((gz) & 3) << 4))
/* A voxel of a group: its word, and the shift of its 16 bits in that word. */
#define VX_NA_VOXEL_WORD(i) ((i) >> 1)
#define VX_NA_VOXEL_SHIFT(i) (((i) & 1) << 4)

#endif
