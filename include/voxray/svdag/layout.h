/* Word layout of the sparse voxel DAG and its index arithmetic, shared by the host builder
 * (svdag/builder.hpp) and the kernel (svdag/kernel.h) in every dialect. Everything is
 * 32-bit words; pointers are word offsets from the start of the blob.
 *
 *  blob
 *  +-------------------------------+ word 0
 *  | header (24 words)             |  magic 'VXSD', version, origin xyz (int), extent xyz,
 *  |                               |  shift xyz, depth D, root, attribute kind and offsets,
 *  |                               |  solid voxels
 *  +-------------------------------+ VX_SV_HEADER_WORDS
 *  | nodes, root first, then the   |  an octree over the cube [0, 2^D)^3 whose identical
 *  | unique nodes level by level   |  subtrees are stored once (a DAG): a node is shared
 *  |                               |  by every parent whose child has the same voxels
 *  +-------------------------------+ header.attributes
 *  | attributes, in depth-first    |  exact:  one payload byte per solid voxel, 4 a word,
 *  | order of the solid voxels     |          low byte first
 *  |                               |  colour blocks: block start indices (sorted), then
 *  |                               |          at header.colours one RGBA8 colour per block
 *  +-------------------------------+
 *
 *  interior node (depth d < D - 2, edge 2^(D-d)) with n children, 2n words (1 for an
 *  empty root):
 *   word 0   . . . . . . . . . . . . . . . . . . . . . . . .  m m m m m m m m
 *            31                                              8 7             0
 *            child mask: bit o set when octant o = x | y<<1 | z<<2 holds a voxel
 *            (x, y, z: the coordinate bit of the child's edge)
 *   word 1+k pointer to the k-th present child, in octant order (k < n)
 *   word n+k solid voxels below children 0 .. k-1, k = 1 .. n-1 (child 0's is 0)
 *
 *            +------+---------+-----+-----------+---------+-----+-----------+
 *            | mask | child 0 | ... | child n-1 | below 1 | ... | below n-1 |
 *            +------+---------+-----+-----------+---------+-----+-----------+
 *
 *  The counts below children (a prefix sum, fixed by the children, so shared nodes stay
 *  shared) make a voxel's depth-first index one load a level, where layout 1 summed the
 *  counts of every sibling before it; the node's own total is not stored (the header has
 *  the root's).
 *
 *  leaf (depth D - 2, a 4x4x4 brick), 2 words: bit x | y<<2 | z<<4 of a 64-bit mask
 *   word 0   z = 0 (bits 0..15) and z = 1 (bits 16..31); word 1: z = 2 and 3
 *
 *  Depth-first index of a solid voxel: the voxels of the siblings before its octant on
 *  every level (the node's count below that child), plus the set bits below its own in
 *  its leaf. It addresses the attributes, which are decoupled from the geometry: a shared
 *  subtree has one geometry but many colours.
 *
 *  Walk coordinates (voxels from the world's min corner) plus shift are DAG coordinates:
 *  the cube's origin is the world's min corner rounded down to a multiple of 16, so that
 *  the model's 16^3 chunks are whole subtrees. */
#ifndef VOXRAY_LAYOUT_SVDAG_LAYOUT_H
#define VOXRAY_LAYOUT_SVDAG_LAYOUT_H

#define VX_SV_MAGIC 0x44535856u /* "VXSD" little endian */
#define VX_SV_VERSION 2u /* 2: counts below the children before each; 1: a count a node */

#define VX_SV_HEADER_MAGIC 0
#define VX_SV_HEADER_VERSION 1
#define VX_SV_HEADER_ORIGIN 2        /* 3 words, signed: world position of walk voxel (0,0,0) */
#define VX_SV_HEADER_EXTENT 5        /* 3 words: world size in voxels */
#define VX_SV_HEADER_SHIFT 8         /* 3 words: DAG coordinate of walk voxel (0,0,0) */
#define VX_SV_HEADER_DEPTH 11        /* D: the cube is 2^D voxels a side */
#define VX_SV_HEADER_ROOT 12         /* pointer to the root (an interior node) */
#define VX_SV_HEADER_ATTRIBUTE_KIND 13
#define VX_SV_HEADER_ATTRIBUTES 14   /* payload bytes, or block starts */
#define VX_SV_HEADER_ATTRIBUTE_COUNT 15 /* solid voxels (exact) or blocks */
#define VX_SV_HEADER_COLOURS 16      /* block colours (colour blocks) */
#define VX_SV_HEADER_SEARCH_TOP 17   /* largest power of two <= block count (binary search) */
#define VX_SV_HEADER_NODE_WORDS 18   /* words of the node region */
#define VX_SV_HEADER_VOXELS 19       /* solid voxels in the DAG */
#define VX_SV_HEADER_WORDS 24

#define VX_SV_ATTRIBUTES_EXACT 0u
#define VX_SV_ATTRIBUTES_COLOUR_BLOCKS 1u

#define VX_SV_MIN_DEPTH 3
#define VX_SV_MAX_DEPTH 17           /* D - 1 stack levels must fit VX_STACK_DEPTH (16) */
#define VX_SV_LEAF_EDGE_BITS 2
#define VX_SV_LEAF_WORDS 2
#define VX_SV_NODE_MASK_BITS 0xFFu
#define VX_SV_NODE_CHILDREN 1        /* word of the first child pointer */
/* Words of an interior node with n children, and the word (from the node) of the count
 * below the children before slot k, for 1 <= k < n. */
#define VX_SV_NODE_WORDS(n) ((n) > 0 ? 2 * (n) : 1)
#define VX_SV_NODE_BELOW(n, k) ((n) + (k))

/* Index arithmetic. Macros, so that one definition serves host integers, GPU integers
 * and SIMD lane vectors alike; `one` is 1u in the lane type (a vector shift needs a
 * vector on its left). (x, y, z) are DAG coordinates. */
#define VX_SV_OCTANT(x, y, z, bit) \
    ((((x) >> (bit)) & 1) | ((((y) >> (bit)) & 1) << 1) | ((((z) >> (bit)) & 1) << 2))
/* The child mask bits below octant o: their popcount is the child's pointer slot. */
#define VX_SV_BELOW(mask, o, one) ((mask) & (((one) << (o)) - 1u))
#define VX_SV_LEAF_BIT(x, y, z) (((x) & 3) | (((y) & 3) << 2) | (((z) & 3) << 4))
#define VX_SV_LEAF_WORD(i) ((i) >> 5)
#define VX_SV_LEAF_SHIFT(i) ((i) & 31)
/* The 8 bits, within the voxel's leaf word, of the 2x2x2 quad holding it. */
#define VX_SV_QUAD_BITS(x, y, one) ((one) * 0x00330033u << (((x) & 2) + (((y) & 2) << 2)))
/* Exact attributes: the word and shift of the byte of depth-first index i. */
#define VX_SV_ATTRIBUTE_WORD(i) ((i) >> 2)
#define VX_SV_ATTRIBUTE_SHIFT(i) (((i) & 3u) * 8u)

#endif
