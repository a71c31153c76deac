/* Byte layout of the dense reference grid, shared by the host builder
 * (structures/dense_grid.hpp asserts against it) and every kernel dialect.
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

#endif
