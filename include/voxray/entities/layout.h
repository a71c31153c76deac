/* Word layout of a scene: a world structure plus instances of entity models (moving,
 * rotated voxel objects), shared by the host (entities/scene.hpp) and the kernels
 * (entities/pass.h, entities/scene_kernel.h) in every dialect. 32-bit words; every offset
 * is in words from the start of the scene blob.
 *
 *  scene blob
 *  +----------------------------+ word 0
 *  | header (16 words)          |  magic 'VXSC', version, world words, instance table,
 *  |                            |  slots, BVH nodes, node count, leaf items, item count,
 *  |                            |  chunk lists (0: none)
 *  +----------------------------+ VX_SC_WORLD (16: 64-byte aligned)
 *  | the world's own blob       |  unchanged: its kernel walks it at this offset
 *  +----------------------------+
 *  | entity models              |  VX_EM_HEADER_WORDS header, occupancy bits, materials
 *  +----------------------------+ header.instances
 *  | instance slots             |  VX_SC_INSTANCE_WORDS each; a free slot has model word
 *  |                            |  VX_SC_FREE_SLOT
 *  +----------------------------+ header.nodes
 *  | BVH nodes                  |  VX_SC_NODE_WORDS each, node 0 the root
 *  +----------------------------+ header.items
 *  | leaf items                 |  instance slot numbers, grouped by leaf
 *  +----------------------------+ header.chunks (where the scene keeps chunk lists)
 *  | chunk lists                |  a word per 16^3 chunk naming the list of instances in it
 *  |                            |  (then the BVH is one leaf: the kernels read its box)
 *  +----------------------------+
 *
 *  instance slot (16 words)                 BVH node (8 words)
 *  0..8   M: world -> model rotation and    0..2  box min x, y, z (float, world voxels)
 *         1/scale, rows (float)             3..5  box max x, y, z
 *  9..11  P: position in the world (float)  6     inner: first child (the second follows)
 *  12..14 C: model point at P, in voxels          leaf:  first leaf item
 *         from the model's min corner       7     0 for an inner node, else the leaf's
 *  15     word offset of the model record         item count
 *
 *  model record: header (16 words)          voxel (x, y, z) of a model, from its min corner:
 *  0      extent x, y, z (3 words)          occupancy bit  x + ex * (y + ey * z) of the bits,
 *  3      min corner x, y, z (int, the      material byte  the same index, 4 a word, low first
 *         model's own coordinates)
 *  6      offset of the occupancy bits     (words from the model record's start, so a
 *  7      offset of the material bytes      record reads the same wherever it lies)
 *  8      offset of the brick fields (0: none, the walk visits every voxel)
 *
 *  brick fields: a word per 4^3 brick of the model's box, brick (x, y, z) at
 *  x + bx * (y + by * z), (bx, by, bz) = extent / 4 rounded up
 *   31  30  29     25 24     20 19     15 14     10 9       5 4       0
 *  +---+---+---------+---------+---------+---------+---------+---------+
 *  | S | 0 |   -z    |   +z    |   -y    |   +y    |   -x    |   +x    |
 *  +---+---+---------+---------+---------+---------+---------+---------+
 *  S = 1: a voxel of the brick is solid (the walk visits its voxels; the fields are 0).
 *  S = 0: the brick is empty, and so is the cuboid of bricks reaching that many bricks
 *  from it in each direction (an axis-aligned distance field, at most 31, never past the
 *  brick grid): the walk leaves the cuboid in one move.
 *
 *  chunk lists (offsets in words from the section's start; chunk (x, y, z) of the grid is
 *  word chunks + x + nx * (y + ny * z))
 *  0..2  grid min corner x, y, z (int, world voxels, multiples of VX_SC_CHUNK_EDGE)
 *  3..5  grid size nx, ny, nz in chunks
 *  6     `chunks`: offset of the chunk words
 *  7     0
 *  8..   per instance slot, its world box: min x, y, z, max x, y, z (float, as a BVH
 *        node's first 6 words; the slots the scene has room for)
 *  chunks..  a word per chunk: 0 where no instance box reaches it, else the offset of its
 *        list
 *  ...   lists: count, then that many instance slots, increasing; chunks with the same
 *        instances share one list
 *
 * A point w of the world lies at model point  M * (w - P) + C  (VX_SC_TO_MODEL): the same
 * float operations, in the same order, on the host's reference and in every kernel, so
 * every backend walks the same model ray. Affine, so t is the same in both frames.
 */
#ifndef VOXRAY_LAYOUT_ENTITIES_LAYOUT_H
#define VOXRAY_LAYOUT_ENTITIES_LAYOUT_H

#define VX_SC_MAGIC 0x43535856u /* "VXSC" little endian */
#define VX_SC_VERSION 3u

#define VX_SC_HEADER_MAGIC 0
#define VX_SC_HEADER_VERSION 1
#define VX_SC_HEADER_WORLD_WORDS 2
#define VX_SC_HEADER_INSTANCES 3
#define VX_SC_HEADER_SLOTS 4
#define VX_SC_HEADER_NODES 5
#define VX_SC_HEADER_NODE_COUNT 6
#define VX_SC_HEADER_ITEMS 7
#define VX_SC_HEADER_ITEM_COUNT 8
/* Offset of the chunk lists; 0 where the scene finds candidates by the BVH alone. */
#define VX_SC_HEADER_CHUNKS 9
#define VX_SC_HEADER_WORDS 16
#define VX_SC_WORLD VX_SC_HEADER_WORDS

#define VX_SC_INSTANCE_WORDS 16
#define VX_SC_INSTANCE_M 0
#define VX_SC_INSTANCE_P 9
#define VX_SC_INSTANCE_C 12
#define VX_SC_INSTANCE_MODEL 15u
#define VX_SC_FREE_SLOT 0xFFFFFFFFu

#define VX_SC_NODE_WORDS 8
#define VX_SC_NODE_MIN 0
#define VX_SC_NODE_MAX 3
#define VX_SC_NODE_FIRST 6
#define VX_SC_NODE_COUNT 7
/* The deepest BVH the host builds (it splits by count, so depth ~ log2 of the instances):
 * the kernel's stack of nodes still to visit holds one sibling per level. */
#define VX_SC_MAX_DEPTH 32

#define VX_SC_CHUNK_MIN 0
#define VX_SC_CHUNK_SIZE 3
#define VX_SC_CHUNK_WORDS 6
#define VX_SC_CHUNK_BOXES 8
#define VX_SC_CHUNK_BOX_WORDS 6
/* Chunk edge in voxels: the paper's 16, and the largest cell vx_dda_begin_scaled takes. */
#define VX_SC_CHUNK_EDGE 16

#define VX_EM_HEADER_WORDS 16
#define VX_EM_EXTENT 0
#define VX_EM_MIN 3
#define VX_EM_BITS 6
#define VX_EM_MATERIALS 7
#define VX_EM_BRICKS 8
/* Brick edge in voxels (a power of two: brick = voxel >> VX_EM_BRICK_SHIFT). */
#define VX_EM_BRICK_SHIFT 2
#define VX_EM_BRICK_EDGE (1 << VX_EM_BRICK_SHIFT)
#define VX_EM_BRICK_SOLID 0x80000000u
#define VX_EM_FIELD_BITS 5u
#define VX_EM_FIELD_MAX 31u
/* Field `dir` (0..5: +x, -x, +y, -y, +z, -z) of an empty brick's word, and the word part
 * that puts `dist` there. */
#define VX_EM_FIELD(word, dir) (((word) >> ((dir) * VX_EM_FIELD_BITS)) & VX_EM_FIELD_MAX)
#define VX_EM_FIELD_PUT(dist, dir) ((dist) << ((dir) * VX_EM_FIELD_BITS))
/* The largest model edge: the bit index of a model voxel stays within 32 bits. */
#define VX_EM_MAX_EDGE 1024

/* A hit on an instance says which one in the material word's upper bits: slot + 1 (0 is
 * the world); the palette index stays in the low byte. */
#define VX_SC_INSTANCE_SHIFT 8u
#define VX_SC_MAX_SLOTS 0xFFFFFFu

/* Model point of world point (wx, wy, wz) along axis row `a` of instance words m[]
 * (any indexable of floats): M * (w - P) + C with a fixed order of operations. */
#define VX_SC_TO_MODEL(m, a, wx, wy, wz)                                                              \
    ((((m)[VX_SC_INSTANCE_M + 3 * (a)] * ((wx) - (m)[VX_SC_INSTANCE_P + 0]) +                          \
       (m)[VX_SC_INSTANCE_M + 3 * (a) + 1] * ((wy) - (m)[VX_SC_INSTANCE_P + 1])) +                      \
      (m)[VX_SC_INSTANCE_M + 3 * (a) + 2] * ((wz) - (m)[VX_SC_INSTANCE_P + 2])) +                       \
     (m)[VX_SC_INSTANCE_C + (a)])
/* Model direction of world direction (dx, dy, dz) along row `a`: M * d. */
#define VX_SC_DIR_TO_MODEL(m, a, dx, dy, dz)                                                          \
    (((m)[VX_SC_INSTANCE_M + 3 * (a)] * (dx) + (m)[VX_SC_INSTANCE_M + 3 * (a) + 1] * (dy)) +            \
     (m)[VX_SC_INSTANCE_M + 3 * (a) + 2] * (dz))

/* Bit index of model voxel (x, y, z) (from the min corner) in a model of extent (ex, ey). */
#define VX_EM_INDEX(x, y, z, ex, ey) ((x) + (ex) * ((y) + (ey) * (z)))

#endif
