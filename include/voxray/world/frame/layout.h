/* Word layout of a world frame: what the GPU-driven passes (world/frame/passes.h, after the
 * paper's section 3.5) read and write, shared by the host (world/frame/frame.hpp) and every
 * dialect. One buffer of 32-bit words; offsets in words from its start.
 *
 *  frame
 *  +------------------------------+ word 0
 *  | header (32 words)            |  camera, screen, counters, capacities, section offsets
 *  +------------------------------+ header[VISIBLE_AT]
 *  | visible chunks: 4 words each |  chunk selection appends: table row, tile rect, near key
 *  +------------------------------+ header[PAIRS_AT]
 *  | tile-chunk pairs: 2 words    |  tile selection appends: tile, visible chunk
 *  +------------------------------+ header[HIZ_AT]
 *  | Hi-Z, 2 x tiles words        |  per tile the farthest depth key of its pixels, twice:
 *  |                              |  the previous frame's and this one's (header[HIZ_PREVIOUS])
 *  +------------------------------+ header[VISIBILITY_AT] (even: 8-byte aligned)
 *  | visibility buffer: 2 words   |  per pixel one 64-bit word, low word first
 *  +------------------------------+ header[MATERIAL_AT]
 *  | material: 1 word per pixel   |  colour resolve: the hit's attribute, as a trace's hit
 *  +------------------------------+
 *
 *  visibility word (Figure 7), the nearest hit wins an atomic max:
 *    bits 63 ........ 40 | 39 .. 37 | 36 ...... 24 | 23 ... 16 | 15 .... 8 | 7 ..... 0
 *         depth key      |   face   |  chunk id    |     z     |     y     |     x
 *  depth key: 2^24 - 1 at the camera down to 0 at the far plane (nearer is larger);
 *  face: VX_FACE_*; chunk id: index into the visible chunks; x y z: the hit's voxel in
 *  the chunk's DAG (so chunks of at most 2^8 voxels a side). 0 means no hit.
 *
 *  visible chunk (4 words): table row (world/layout.h) | tile rect min tx | ty << 16 |
 *  tile rect max (inclusive) alike | near key: the largest depth key a hit in the chunk
 *  can have (from the box's nearest depth; 2^24 - 1 when the camera is in or beside it).
 *
 * Rays: pixel (px, py) looks along F + a R + b U from the camera, with
 * a = (px + 0.5) * 2 / width - 1 and b = 1 - (py + 0.5) * 2 / height; F is the unit view
 * direction, R and U are the right and up vectors scaled by the half-extent of the view
 * (tan of half the field of view), both orthogonal to F. So a hit's t is its depth along F. */
#ifndef VOXRAY_LAYOUT_WORLD_FRAME_LAYOUT_H
#define VOXRAY_LAYOUT_WORLD_FRAME_LAYOUT_H

#define VX_WF_HEADER_WIDTH 0
#define VX_WF_HEADER_HEIGHT 1
#define VX_WF_HEADER_TILES_X 2
#define VX_WF_HEADER_TILES_Y 3
#define VX_WF_HEADER_CAMERA 4          /* 3 floats: position (world) */
#define VX_WF_HEADER_FORWARD 7         /* 3 floats: F */
#define VX_WF_HEADER_RIGHT 10          /* 3 floats: R */
#define VX_WF_HEADER_UP 13             /* 3 floats: U */
#define VX_WF_HEADER_PIXEL_SCALE 16    /* 2 floats: 2 / width, 2 / height */
#define VX_WF_HEADER_DEPTH_SCALE 18    /* float: (2^24 - 1) / far */
#define VX_WF_HEADER_VISIBLE_COUNT 19  /* counter (chunk selection) */
#define VX_WF_HEADER_VISIBLE_CAPACITY 20
#define VX_WF_HEADER_PAIR_COUNT 21     /* counter (tile selection) */
#define VX_WF_HEADER_PAIR_CAPACITY 22
#define VX_WF_HEADER_HIZ_PREVIOUS 23   /* 0 or 1: which Hi-Z array is the previous frame's */
#define VX_WF_HEADER_VISIBLE_AT 24
#define VX_WF_HEADER_PAIRS_AT 25
#define VX_WF_HEADER_HIZ_AT 26
#define VX_WF_HEADER_VISIBILITY_AT 27
#define VX_WF_HEADER_MATERIAL_AT 28
#define VX_WF_HEADER_WORDS 32

#define VX_WF_TILE_BITS 3              /* 8 x 8 pixel tiles */
#define VX_WF_TILE_PIXELS 64
#define VX_WF_VISIBLE_WORDS 4
#define VX_WF_PAIR_WORDS 2

#define VX_WF_DEPTH_MAX 16777215u      /* 2^24 - 1 */
#define VX_WF_MAX_CHUNKS 8192u         /* 13-bit chunk ids */
#define VX_WF_MAX_CHUNK_BITS 8         /* 8 bits a voxel coordinate */

/* The visibility word as (hi, lo) 32-bit halves. */
#define VX_WF_PACK_HI(depth, face, chunk) (((depth) << 8) | ((face) << 5) | ((chunk) >> 8))
#define VX_WF_PACK_LO(chunk, x, y, z) ((((chunk) & 255u) << 24) | ((z) << 16) | ((y) << 8) | (x))
#define VX_WF_DEPTH(hi) ((hi) >> 8)
#define VX_WF_FACE(hi) (((hi) >> 5) & 7u)
#define VX_WF_CHUNK(hi, lo) ((((hi) & 31u) << 8) | ((lo) >> 24))
#define VX_WF_X(lo) ((lo) & 255u)
#define VX_WF_Y(lo) (((lo) >> 8) & 255u)
#define VX_WF_Z(lo) (((lo) >> 16) & 255u)

/* Passes, in frame order: clear; select chunks; select tiles against the previous Hi-Z;
 * march; build Hi-Z; select the tiles that pass culled and pass now; march; build Hi-Z;
 * resolve. Items per pass: pixels, table rows, visible chunks, pairs x 64, tiles, pixels. */
#define VX_WF_PASS_CLEAR 0u
#define VX_WF_PASS_SELECT_CHUNKS 1u
#define VX_WF_PASS_SELECT_TILES 2u
#define VX_WF_PASS_SELECT_TILES_AGAIN 3u
#define VX_WF_PASS_MARCH 4u
#define VX_WF_PASS_BUILD_HIZ 5u
#define VX_WF_PASS_RESOLVE 6u
#define VX_WF_PASSES 7u

#endif
