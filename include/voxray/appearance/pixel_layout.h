/* What the compositing walk (walk.inc) returns for one ray, as it travels from every
 * backend to the host. C-compatible: included by C++ (appearance/pixel.hpp asserts its
 * layout against these numbers), by OpenCL C and by GLSL (through walk_types.h). All fields
 * are 32-bit, so the std430 array stride is the size.
 *
 *  vx_app_walk_result (64 bytes, 16 words)
 *  word 0..2  colour r, g, b    (float, linear, blended front to back)
 *  word 3     transmittance     (float, what is left of the ray: 1 for a miss)
 *  word 4     t                 (float, the first voxel's entry t)
 *  word 5..7  voxel x, y, z     (int, the first voxel)
 *  word 8     face              (uint, VX_FACE_*, how the first voxel was entered)
 *  word 9     material          (uint, the first voxel's palette index)
 *  word 10    visits            (uint, voxels blended)
 *  word 11    steps             (uint, the structure kernel's steps over every re-entry)
 *  word 12    status            (uint, VX_STATUS_HIT or _MISS, or VX_APP_WALK_NO_RECORD)
 *  word 13..15 normal x, y, z   (float, the voxels' normals turned to the viewer, blended
 *                                with the colour's weights: length 1 - transmittance at most)
 */
#ifndef VOXRAY_APPEARANCE_PIXEL_LAYOUT_H
#define VOXRAY_APPEARANCE_PIXEL_LAYOUT_H

#define VX_APP_PIXEL_BYTES 64
#define VX_APP_PIXEL_OFFSET_COLOUR 0
#define VX_APP_PIXEL_OFFSET_TRANSMITTANCE 12
#define VX_APP_PIXEL_OFFSET_T 16
#define VX_APP_PIXEL_OFFSET_VOXEL 20
#define VX_APP_PIXEL_OFFSET_FACE 32
#define VX_APP_PIXEL_OFFSET_MATERIAL 36
#define VX_APP_PIXEL_OFFSET_VISITS 40
#define VX_APP_PIXEL_OFFSET_STEPS 44
#define VX_APP_PIXEL_OFFSET_STATUS 48
#define VX_APP_PIXEL_OFFSET_NORMAL 52

/* The walk met a voxel the ordinal index does not know: the table is not this structure's. */
#define VX_APP_WALK_NO_RECORD 3u

/* Record kinds of a table, as the walk's `kind` argument. */
#define VX_APP_KIND_AVERAGES 0u
#define VX_APP_KIND_COMPACT 1u
#define VX_APP_KIND_SIX 2u
#define VX_APP_KIND_SGGX 3u
#define VX_APP_KIND_FAITHFUL 4u

#endif
