/* Byte layout of the dense reference grid and its address arithmetic, shared by the host
 * builder (dense_grid/dense_grid.hpp) and the kernel (dense_grid/kernel.h) in every dialect.
 * Everything is 32-bit words; offsets are in words from the start of the blob.
 *
 *  blob
 *  +--------------------------+ word 0
 *  | header (16 words)        |  magic 'VXDG', version, origin xyz (int), extent xyz,
 *  |                          |  chunk grid xyz, table offset, data offset, chunk count
 *  +--------------------------+ VX_DG_TABLE (header.table_offset)
 *  | chunk table              |  one word per 16^3 chunk, x fastest, then y, then z:
 *  |                          |  VX_DG_EMPTY_CHUNK or the index of the chunk's record
 *  +--------------------------+ header.data_offset
 *  | chunk records            |  VX_DG_CHUNK_WORDS each:
 *  |  [0..127]   occupancy    |    bit  (lx | ly<<4 | lz<<8) of the 4096-bit mask
 *  |  [128..1151] materials   |    byte (lx | ly<<4 | lz<<8), 4 per word, low byte first
 *  +--------------------------+
 *
 *  local voxel index within a chunk (12 bits):  z z z z y y y y x x x x
 *                                               11    8 7     4 3     0
 */
#ifndef VOXRAY_LAYOUT_DENSE_GRID_LAYOUT_H
#define VOXRAY_LAYOUT_DENSE_GRID_LAYOUT_H

#define VX_DG_MAGIC 0x47445856u /* "VXDG" little endian */
#define VX_DG_VERSION 1u

#define VX_DG_HEADER_MAGIC 0
#define VX_DG_HEADER_VERSION 1
#define VX_DG_HEADER_ORIGIN 2       /* 3 words, signed */
#define VX_DG_HEADER_EXTENT 5       /* 3 words */
#define VX_DG_HEADER_CHUNKS 8       /* 3 words: chunk grid dimensions */
#define VX_DG_HEADER_TABLE 11
#define VX_DG_HEADER_DATA 12
#define VX_DG_HEADER_CHUNK_COUNT 13
#define VX_DG_HEADER_WORDS 16

#define VX_DG_CHUNK_BITS 4
#define VX_DG_CHUNK_EDGE 16
#define VX_DG_CHUNK_MASK 15
#define VX_DG_OCCUPANCY_WORDS 128   /* 4096 bits */
#define VX_DG_MATERIAL_WORDS 1024   /* 4096 bytes */
#define VX_DG_CHUNK_WORDS 1152
#define VX_DG_EMPTY_CHUNK 0xFFFFFFFFu

/* Address arithmetic. Macros, so that one definition serves host integers, GPU integers
 * and SIMD lane vectors alike. (x, y, z) are voxel coordinates relative to the grid's
 * origin; chunks_x and chunks_xy = chunks_x * chunks_y come from the header. */
#define VX_DG_LOCAL(x, y, z) \
    (((x) & VX_DG_CHUNK_MASK) | (((y) & VX_DG_CHUNK_MASK) << 4) | (((z) & VX_DG_CHUNK_MASK) << 8))
#define VX_DG_CHUNK_SLOT(x, y, z, chunks_x, chunks_xy) \
    (((x) >> VX_DG_CHUNK_BITS) + ((y) >> VX_DG_CHUNK_BITS) * (chunks_x) + ((z) >> VX_DG_CHUNK_BITS) * (chunks_xy))
/* Word (within a chunk record) of local voxel l's occupancy bit and of its material byte. */
#define VX_DG_OCCUPANCY_WORD(l) ((l) >> 5)
#define VX_DG_MATERIAL_WORD(l) (VX_DG_OCCUPANCY_WORDS + ((l) >> 2))
#define VX_DG_MATERIAL_SHIFT(l) (((l) & 3u) * 8u)

#endif
