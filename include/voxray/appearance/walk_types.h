/* What the compositing walk (walk.inc) returns (its layout: pixel_layout.h), and the
 * helpers it shares across structures: a voxel's exit along a ray, and a record's sample
 * by kind. Needs prelude.h, kernels/ray.h, record.h, faithful_record.h and ordinal.h. Included once per lane
 * set; no include guard. */
#include "voxray/appearance/pixel_layout.h"

VX_STRUCT(vx_app_walk_result)
    float r, g, b;        /* linear colour blended front to back */
    float transmittance;  /* what is left of the ray: 1 for a miss */
    float t;              /* the first voxel's entry t */
    int x, y, z;          /* the first voxel */
    uint face;            /* the face the first voxel was entered through */
    uint material;        /* the first voxel's palette index */
    uint visits;          /* voxels blended */
    uint steps;           /* the structure kernel's steps, over every re-entry */
    uint status;          /* VX_STATUS_HIT or _MISS for the first voxel, or VX_APP_WALK_NO_RECORD */
    float nx, ny, nz;     /* normals blended like the colour */
VX_END_STRUCT(vx_app_walk_result)

VX_APP_FN vx_app_walk_result vx_app_walk_start(void) {
    vx_app_walk_result w;
    w.r = 0.0f, w.g = 0.0f, w.b = 0.0f, w.transmittance = 1.0f, w.t = VX_INF;
    w.x = 0, w.y = 0, w.z = 0, w.face = VX_FACE_NONE, w.material = 0u;
    w.visits = 0u, w.steps = 0u, w.status = VX_STATUS_MISS;
    w.nx = 0.0f, w.ny = 0.0f, w.nz = 0.0f;
    return w;
}

/* A walk under way (walk.inc): what it has blended, the voxel it blended last (and the normal
 * it showed) and the run of touching voxels that voxel ends (the run's transmittance before
 * it, its coverage so far).
 * A walk through several pieces walked one after another (a world's chunks:
 * appearance/world/placed_walker.hpp) hands the state on, so that a surface crossing from one
 * piece into the next stays one run, as in one piece. */
VX_STRUCT(vx_app_walk_state)
    vx_app_walk_result w;
    int px, py, pz;
    float pnx, pny, pnz;
    float run_t, run_covered;
VX_END_STRUCT(vx_app_walk_state)

VX_APP_FN vx_app_walk_state vx_app_walk_state_start(void) {
    vx_app_walk_state s;
    s.w = vx_app_walk_start();
    s.px = 0, s.py = 0, s.pz = 0;
    s.pnx = 0.0f, s.pny = 0.0f, s.pnz = 0.0f;
    s.run_t = 1.0f, s.run_covered = 0.0f;
    return s;
}

/* t at which a ray along one axis (origin o, direction d) leaves cell c: its far plane. */
VX_APP_FN float vx_app_exit_axis(float o, float d, int c) {
    return d > 0.0f ? (vx_i2f(c + 1) - o) / d : (d < 0.0f ? (vx_i2f(c) - o) / d : VX_INF);
}

/* The voxel ray r enters when it leaves voxel (x, y, z), across the far plane it meets
 * first, and where: t, the nearest far plane of the moving axes. tie is 1 when two or three
 * planes are met at once (an edge or a corner): the next voxel is then not one face away,
 * and the caller does not step. */
VX_STRUCT(vx_app_next)
    int x, y, z;
    float t;
    uint tie;
VX_END_STRUCT(vx_app_next)

VX_APP_FN vx_app_next vx_app_next_voxel(vx_ray r, int x, int y, int z) {
    float tx = vx_app_exit_axis(r.ox, r.dx, x), ty = vx_app_exit_axis(r.oy, r.dy, y);
    float tz = vx_app_exit_axis(r.oz, r.dz, z);
    vx_app_next n;
    n.x = x, n.y = y, n.z = z;
    n.t = vx_fmin(vx_fmin(tx, ty), tz);
    n.tie = (tx == n.t ? 1u : 0u) + (ty == n.t ? 1u : 0u) + (tz == n.t ? 1u : 0u) > 1u ? 1u : 0u;
    if (tx == n.t) n.x = x + (r.dx > 0.0f ? 1 : -1);
    else if (ty == n.t) n.y = y + (r.dy > 0.0f ? 1 : -1);
    else n.z = z + (r.dz > 0.0f ? 1 : -1);
    return n;
}

/* Row `row` of a table of `kind` records, along unit direction (dx, dy, dz). */
VX_APP_FN vx_app_sample vx_app_record_sample(VX_BLOB records, VX_BLOB faces, uint kind, uint row, float dx, float dy,
                                             float dz, vx_app_light light) {
    if (kind == VX_APP_KIND_AVERAGES)
        return vx_app_averages_sample(vx_blob_at(records, row * VX_APP_AVERAGES_WORDS), dx, dy, dz, light);
    if (kind == VX_APP_KIND_SIX) return vx_app_six_sample(vx_blob_at(records, row * VX_APP_SIX_WORDS), dx, dy, dz);
    if (kind == VX_APP_KIND_FAITHFUL)
        return vx_app_faithful_sample(vx_blob_at(records, row * VX_APP_FAITHFUL_WORDS), dx, dy, dz, light);
    if (kind == VX_APP_KIND_SGGX)
        return vx_app_sggx_sample(vx_blob_at(records, row * VX_APP_SGGX_WORDS), dx, dy, dz, light);
    return vx_app_compact_sample(records, faces, row, dx, dy, dz, light);
}
