/* The kernel of a scene over one kind of world (entities/layout.h): the world's own walk on
 * its words at VX_SC_WORLD, then the entity pass (entities/pass.h) up to the world's hit.
 * Written once for every world kind: entities/worlds/<world>.h includes it with
 *   VX_SCENE_WORLD   the world kernel's name (naadf: its functions are vx_naadf_*),
 *   VX_SCENE_HEADER  the type its _load returns,  VX_SCENE_STATE  the type its _begin returns,
 * (a world kernel's _finish takes the ray its walk began with, as every kernel's does),
 * and gets vx_scene_<world>_load, _begin, _step, _status, _finish and _trace, and the trace in
 * two stages, _first and _then (OpenCL: two kernels, docs/design.md "Staged kernels").
 * No include guard: once per world kind and lane set (see kernels/kernel_tag.inc). */
#if !defined(VX_SCENE_WORLD) || !defined(VX_SCENE_HEADER) || !defined(VX_SCENE_STATE)
#error "define VX_SCENE_WORLD, VX_SCENE_HEADER and VX_SCENE_STATE before including entities/scene_kernel.h"
#endif

#define VX_SC_PASTE_(a, b, c) a##b##c
#define VX_SC_PASTE(a, b, c) VX_SC_PASTE_(a, b, c)
#define VX_SC_WORLD_FN(f) VX_SC_PASTE(vx_, VX_SCENE_WORLD, f)
#define VX_SC_SCENE_FN(f) VX_SC_PASTE(vx_scene_, VX_SCENE_WORLD, f)

/* The world's walk state. The entity pass also needs the ray, which finish is given: a
 * copy in the state would be stepped and merged with it (on 16 SIMD lanes that made the
 * world's walk 3x slower, measured). */
VX_STRUCT(VX_SC_SCENE_FN(_state))
    VX_SCENE_STATE w;
VX_END_STRUCT(VX_SC_SCENE_FN(_state))

VX_FN VX_SCENE_HEADER VX_SC_SCENE_FN(_load)(VX_BLOB blob) {
    return VX_SC_WORLD_FN(_load)(vx_blob_at(blob, VX_SC_WORLD));
}

VX_FN VX_SC_SCENE_FN(_state) VX_SC_SCENE_FN(_begin)(VX_SCENE_HEADER g, vx_ray r) {
    VX_SC_SCENE_FN(_state) s;
    s.w = VX_SC_WORLD_FN(_begin)(g, r);
    return s;
}

VX_FN VX_SC_SCENE_FN(_state) VX_SC_SCENE_FN(_step)(VX_BLOB blob, VX_SCENE_HEADER g, VX_SC_SCENE_FN(_state) s) {
    s.w = VX_SC_WORLD_FN(_step)(vx_blob_at(blob, VX_SC_WORLD), g, s.w);
    return s;
}

VX_FN vx_u32 VX_SC_SCENE_FN(_status)(VX_SC_SCENE_FN(_state) s) { return VX_SC_WORLD_FN(_status)(s.w); }

/* The entity pass after the world's hit h, in the lanes of `done` whose ray enters the
 * instances' box (every backend filters alike, so steps agree). The pass is scalar code
 * (entities/pass.h): the C++ lanes run it for each such lane in turn. */
VX_FN vx_hit VX_SC_SCENE_FN(_entities)(VX_BLOB blob, vx_ray r, vx_hit h, vx_mask done, uint mode) {
    vx_mask go = done && vx_sc_enters_entities(blob, r, h);
#if defined(VX_DIALECT_CPP)
    return vx_each_lane(go, r, h, [&](const scalar::vx_ray& lane_ray, const scalar::vx_hit& world_hit) {
        return scalar::vx_entities_trace(blob, lane_ray, world_hit, mode);
    });
#else
    return go ? vx_entities_trace(blob, r, h, mode) : h;
#endif
}

/* The world's hit, then the entities, in every lane whose world walk has ended. */
VX_FN vx_hit VX_SC_SCENE_FN(_finish)(VX_BLOB blob, VX_SCENE_HEADER g, VX_SC_SCENE_FN(_state) s, vx_ray r, uint mode) {
    vx_hit h = VX_SC_WORLD_FN(_finish)(vx_blob_at(blob, VX_SC_WORLD), g, s.w, r, mode);
    return VX_SC_SCENE_FN(_entities)(blob, r, h, VX_SC_WORLD_FN(_status)(s.w) != VX_STATUS_ACTIVE, mode);
}

/* The two stages of one ray's trace, which the OpenCL backend runs as two kernels (the
 * kernel is registered STAGED): the world's own trace on its words, then the entities on
 * its hit. Apart, the world's walk compiles as it does alone: the entity pass's code in
 * the same kernel slowed PoCL's world walk even for rays that never ran it. */
VX_FN vx_hit VX_SC_SCENE_FN(_first)(VX_BLOB blob, vx_ray r, uint mode) {
    return VX_SC_WORLD_FN(_trace)(vx_blob_at(blob, VX_SC_WORLD), r, mode);
}

VX_FN vx_hit VX_SC_SCENE_FN(_then)(VX_BLOB blob, vx_ray r, vx_hit h, uint mode) {
    return VX_SC_SCENE_FN(_entities)(blob, r, h, h.status != VX_STATUS_ACTIVE, mode);
}

/* One ray (Vulkan invocations, the C++ scalar lanes' single rays): both stages in turn. */
VX_FN vx_hit VX_SC_SCENE_FN(_trace)(VX_BLOB blob, vx_ray r, uint mode) {
    return VX_SC_SCENE_FN(_then)(blob, r, VX_SC_SCENE_FN(_first)(blob, r, mode), mode);
}

#undef VX_SC_SCENE_FN
#undef VX_SC_WORLD_FN
#undef VX_SC_PASTE
#undef VX_SC_PASTE_
