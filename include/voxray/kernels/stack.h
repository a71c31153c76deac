/* A per-lane stack indexed by level, for traversals that descend a tree and come back up
 * (the sparse voxel DAG keeps, per level, the node it came from). One source, three
 * storage forms:
 *   GPU dialects and scalar C++ lanes: a plain array, slot[level];
 *   SIMD lanes: the same array of lane vectors, so slot[d] holds every lane's entry at depth
 *   d (lane-interleaved), and each lane reaches its own level by masked selects.
 * A stack is a kernel-state field like any other (rows of lane vectors), so the CPU stream
 * merges it generically. It is passed in place (VX_INOUT): at 16 lanes it is 1 KiB.
 *
 *   vx_stack_store(VX_ADDR(s.stack), level, value, m)   slot[level] = value in lanes m
 *   vx_stack_load(VX_ADDR(s.stack), level)              slot[level] of every lane
 *
 * Levels must lie in [0, VX_STACK_DEPTH); the caller's depth bound keeps them there.
 * Included once per lane set; no include guard on purpose (see cpu/lanes.hpp). */
#ifndef VX_STACK_DEPTH
#define VX_STACK_DEPTH 16
#endif

VX_STRUCT(vx_stack)
    vx_u32 slot[VX_STACK_DEPTH];
VX_END_STRUCT(vx_stack)

#if defined(VX_SIMD_WIDTH)
/* SIMD lanes: every depth is one lane vector, and a lane's own level is picked by a select
 * per depth (no scatter or gather through a pointer into the state, which the compiler's
 * aliasing rules would have to be trusted with; a stack operation is per descent, not per
 * step, so its VX_STACK_DEPTH selects are cheap next to the traversal). */
inline void vx_stack_store(vx_stack& s, vx_i32 level, vx_u32 value, vx_mask m) {
#pragma GCC unroll 32
    for (int d = 0; d < VX_STACK_DEPTH; ++d) s.slot[d] = vx_sel(m && level == d, value, s.slot[d]);
}
inline vx_u32 vx_stack_load(vx_stack& s, vx_i32 level) {
    vx_u32 value = vx_u32_splat(0u);
#pragma GCC unroll 32
    for (int d = 0; d < VX_STACK_DEPTH; ++d) value = vx_sel(level == d, s.slot[d], value);
    return value;
}
#else
/* One lane a thread: the level is this lane's, the array is indexed directly. */
VX_FN void vx_stack_store(VX_INOUT(vx_stack) s, vx_i32 level, vx_u32 value, vx_mask m) {
    if (m) VX_REF(s).slot[level] = value;
}
VX_FN vx_u32 vx_stack_load(VX_INOUT(vx_stack) s, vx_i32 level) { return VX_REF(s).slot[level]; }
#endif
