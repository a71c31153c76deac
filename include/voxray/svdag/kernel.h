/* Traversal of the sparse voxel DAG (svdag/layout.h): the DAG walk of svdag/walk.h over
 * the one DAG at word 0, in walk voxels from the world's min corner, then, for closest
 * hits only, the hit voxel's attribute (depth-first index, then payload byte or colour
 * block). Needs prelude.h, ray.h, dda.h, stack.h, bits.h, svdag/walk.h. Included once per
 * lane set; no include guard on purpose. */
#include "voxray/svdag/layout.h"

VX_STRUCT(vx_svdag)
    vx_sv_frame f;        /* depth, walk-to-DAG shift, the world's size in voxels */
    int ox, oy, oz;       /* world position of walk voxel (0,0,0) */
    uint attribute_kind;
VX_END_STRUCT(vx_svdag)

VX_FN vx_svdag vx_svdag_load(VX_BLOB blob) {
    vx_svdag g;
    g.ox = vx_u2i(vx_load(blob, VX_SV_HEADER_ORIGIN + 0));
    g.oy = vx_u2i(vx_load(blob, VX_SV_HEADER_ORIGIN + 1));
    g.oz = vx_u2i(vx_load(blob, VX_SV_HEADER_ORIGIN + 2));
    g.f.ex = vx_u2i(vx_load(blob, VX_SV_HEADER_EXTENT + 0));
    g.f.ey = vx_u2i(vx_load(blob, VX_SV_HEADER_EXTENT + 1));
    g.f.ez = vx_u2i(vx_load(blob, VX_SV_HEADER_EXTENT + 2));
    g.f.shx = vx_u2i(vx_load(blob, VX_SV_HEADER_SHIFT + 0));
    g.f.shy = vx_u2i(vx_load(blob, VX_SV_HEADER_SHIFT + 1));
    g.f.shz = vx_u2i(vx_load(blob, VX_SV_HEADER_SHIFT + 2));
    g.f.depth = vx_u2i(vx_load(blob, VX_SV_HEADER_DEPTH));
    g.attribute_kind = vx_load(blob, VX_SV_HEADER_ATTRIBUTE_KIND);
    return g;
}

/* Every lane starts at the root of the DAG at word 0 (its cube holds the whole world). */
VX_FN vx_sv_state vx_svdag_begin(vx_svdag g, vx_ray r) {
    vx_sv_state s = vx_sv_begin(g.f, r, g.ox, g.oy, g.oz);
    vx_mask every_lane = vx_u32_splat(0u) == 0u;
    return vx_sv_enter(s, vx_u32_splat(0u), vx_u32_splat(0u), every_lane);
}

/* Lanes m restarted with new rays (walk s, just begun) after walk `old` ended: the CPU
 * stream's refill starts each at the deepest node old's path shares with it. */
VX_FN vx_sv_state vx_svdag_resume(vx_svdag g, vx_sv_state old, vx_sv_state s, vx_mask m) {
    return vx_sv_resume(g.f, old, s, m);
}

VX_FN vx_sv_state vx_svdag_step(VX_BLOB blob, vx_svdag g, vx_sv_state s) {
    return vx_sv_step(blob, g.f, s, s.w.status == VX_STATUS_ACTIVE);
}

VX_FN vx_u32 vx_svdag_status(vx_sv_state s) { return s.w.status; }

/* The hit record; any-hit (a constant `mode`) skips the attribute lookup. */
VX_FN vx_hit vx_svdag_finish(VX_BLOB blob, vx_svdag g, vx_sv_state s, vx_ray r, uint mode) {
    VX_UNUSED(r);
    vx_mask is_hit = s.w.status == VX_STATUS_HIT;
    vx_u32 material = vx_u32_splat(0u);
    if (mode == VX_MODE_CLOSEST) material = vx_sv_material(blob, g.f, g.attribute_kind, s, is_hit);
    return vx_hit_from_walk(s.w, g.ox, g.oy, g.oz, material);
}

/* Closest hit, or any hit (the first solid voxel serves both; any-hit skips attributes). */
VX_FN vx_hit vx_svdag_trace(VX_BLOB blob, vx_ray r, uint mode) {
    vx_svdag g = vx_svdag_load(blob);
    vx_sv_state s = vx_svdag_begin(g, r);
    while (vx_any(s.w.status == VX_STATUS_ACTIVE)) s = vx_svdag_step(blob, g, s);
    return vx_svdag_finish(blob, g, s, r, mode);
}
