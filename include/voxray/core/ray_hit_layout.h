/* Ray and hit records as they travel between host and every backend.
 * C-compatible: included by C++ (core/ray.hpp, core/hit.hpp assert their layout against
 * these numbers), by OpenCL C and by GLSL. All fields are 32-bit.
 *
 *  vx_ray (32 bytes)                      vx_hit (32 bytes)
 *  word 0..2  origin x, y, z  (float)     word 0     t         (float)
 *  word 3     tmin            (float)     word 1..3  voxel x,y,z (int)
 *  word 4..6  direction x,y,z (float)     word 4     face      (uint, VX_FACE_*)
 *  word 7     tmax            (float)     word 5     material  (uint, palette index)
 *                                         word 6     steps     (uint)
 *                                         word 7     status    (uint, VX_STATUS_*)
 */
#ifndef VOXRAY_LAYOUT_RAY_HIT_LAYOUT_H
#define VOXRAY_LAYOUT_RAY_HIT_LAYOUT_H

#define VX_RAY_BYTES 32
#define VX_RAY_OFFSET_ORIGIN 0
#define VX_RAY_OFFSET_TMIN 12
#define VX_RAY_OFFSET_DIRECTION 16
#define VX_RAY_OFFSET_TMAX 28

#define VX_HIT_BYTES 32
#define VX_HIT_OFFSET_T 0
#define VX_HIT_OFFSET_VOXEL 4
#define VX_HIT_OFFSET_FACE 16
#define VX_HIT_OFFSET_MATERIAL 20
#define VX_HIT_OFFSET_STEPS 24
#define VX_HIT_OFFSET_STATUS 28

/* Faces are outward normals of the hit voxel: axis * 2 + (negative ? 1 : 0). */
#define VX_FACE_POS_X 0u
#define VX_FACE_NEG_X 1u
#define VX_FACE_POS_Y 2u
#define VX_FACE_NEG_Y 3u
#define VX_FACE_POS_Z 4u
#define VX_FACE_NEG_Z 5u
#define VX_FACE_INSIDE 6u
#define VX_FACE_NONE 7u

/* Traversal status; a finished ray is a hit or a miss. */
#define VX_STATUS_ACTIVE 0u
#define VX_STATUS_HIT 1u
#define VX_STATUS_MISS 2u

/* Trace modes. Any-hit may return any solid voxel on the ray (shadow rays). */
#define VX_MODE_CLOSEST 0u
#define VX_MODE_ANY 1u

#endif
