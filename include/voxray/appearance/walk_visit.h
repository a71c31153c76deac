/* One visit of the compositing walk (walk.inc), written once for every structure and every
 * way of driving the walk: a cursor holds a walk under way, and vx_app_walk_visit takes the
 * closest hit of the cursor's ray, blends that voxel's record into the cursor's state (and
 * the records of the voxels the ray goes on into face to face: a DDA step each, where a
 * re-entry into the structure would cost a closest hit) and moves the ray on past them. The
 * walk is
 *
 *     c = vx_app_walk_begin(r, s, max_visits);
 *     while (c.going != 0u) c = vx_app_walk_visit(..., closest_hit(c.r), c);
 *
 * which walk.inc writes as one loop per ray (GPUs, the CPU's scalar lanes). A visit is
 *
 *     c = vx_app_walk_enter(index, max_visits, h, c);   (c.row: the voxel to blend, if any)
 *     while (c.row != VX_APP_NO_ROW)
 *         c = vx_app_walk_take(index, kind, cutoff, max_visits, vx_app_walk_sample(..., c), c);
 *
 * and the CPU's SIMD walk (cpu/appearance_walk.hpp) runs its parts as rounds: the closest
 * hits of every walking cursor's ray on SIMD lanes, then each one's enter, then, while any
 * cursor has a voxel to blend, their records' samples on SIMD lanes and a take each. All
 * give the same state bit for bit. Users' shaders can drive it with their own trace too.
 * Needs walk_types.h. Included once per lane set; no include guard.
 *
 * Unlike the records' functions, these are not `precise` in GLSL: glslang's precise
 * propagation through a cursor (a struct in a struct, assigned field by field) grows without
 * bound (over 20 GB for one module). Their own sums and products go through
 * vx_app_add_product, which is, so no compiler fuses them and every backend rounds alike. */

/* sum + x y z, rounded as written on every backend (no fused multiply-add). */
VX_APP_FN float vx_app_add_product(float sum, float x, float y, float z) { return sum + x * y * z; }

/* The least cosine between the normals two touching voxels show for them to be one sheet
 * (about 18 degrees apart): see vx_app_walk_blend. */
#define VX_APP_SHEET_COS 0.95f

/* Whether unit normals (ax, ay, az) and (bx, by, bz), as two voxels show them, lie within
 * VX_APP_SHEET_COS of each other; a voxel that shows no normal (0) goes with any. */
VX_FN bool vx_app_walk_one_sheet(float ax, float ay, float az, float bx, float by, float bz) {
    if ((ax == 0.0f && ay == 0.0f && az == 0.0f) || (bx == 0.0f && by == 0.0f && bz == 0.0f)) return true;
    float d = vx_app_add_product(0.0f, ax, bx, 1.0f);
    d = vx_app_add_product(d, ay, by, 1.0f);
    d = vx_app_add_product(d, az, bz, 1.0f);
    return d >= VX_APP_SHEET_COS;
}

VX_STRUCT(vx_app_walk_cursor)
    vx_app_walk_state s;
    vx_ray r;     /* the ray; its tmin moves past each voxel walked */
    float nudge;  /* how far past a voxel's exit a re-entry starts (relative to max(t, 1)) */
    uint tries;   /* closest hits taken */
    uint going;   /* 1 while the walk wants the closest hit along r (or has a voxel to blend) */
    uint row;     /* the record of the voxel to blend next, VX_APP_NO_ROW when none */
    int x, y, z;  /* that voxel */
VX_END_STRUCT(vx_app_walk_cursor)

/* A walk of at most `max_visits` voxels and 4 max_visits closest hits along r, going on from s. */
VX_FN vx_app_walk_cursor vx_app_walk_begin(vx_ray r, vx_app_walk_state s, uint max_visits) {
    vx_app_walk_cursor c;
    c.s = s, c.r = r, c.nudge = 1.0e-6f, c.tries = 0u;
    c.going = s.w.visits < max_visits ? 1u : 0u;
    c.row = VX_APP_NO_ROW, c.x = 0, c.y = 0, c.z = 0;
    return c;
}

/* The light that reaches row `row`: precomputed shadows (appearance/shadows.hpp), where
 * `shadows_at` is not 0, are a visibility byte a row in `records` from that word on (four a
 * word, row 0 in the low byte), which scales the light. */
VX_FN vx_app_light vx_app_walk_light(VX_BLOB records, vx_app_light light, uint shadows_at, uint row) {
    vx_app_light lit = light;
    if (shadows_at != 0u) {
        uint code = (vx_load(records, shadows_at + (row >> 2u)) >> ((row & 3u) * 8u)) & 255u;
        float visibility = vx_u2f(code) * (1.0f / 255.0f);
        lit.lx = light.lx * visibility, lit.ly = light.ly * visibility, lit.lz = light.lz * visibility;
    }
    return lit;
}

/* What the voxel the cursor is to blend next (c.row) shows along its ray. */
VX_FN vx_app_sample vx_app_walk_sample(VX_BLOB records, VX_BLOB faces, uint kind, vx_app_light light,
                                       uint shadows_at, vx_app_walk_cursor c) {
    return vx_app_record_sample(records, faces, kind, c.row, c.r.dx, c.r.dy, c.r.dz,
                                vx_app_walk_light(records, light, shadows_at, c.row));
}

/* Blends `seen`, what voxel (x, y, z) shows, into the cursor's state: C += T a c, T *= 1 - a. */
VX_FN vx_app_walk_cursor vx_app_walk_blend(vx_app_sample seen, uint kind, int x, int y, int z,
                                           vx_app_walk_cursor c) {
    /* A run of touching voxels that show one sheet (their normals within VX_APP_SHEET_COS)
     * is one surface crossing: their coverages add up (a line crosses a sheet once). Voxels
     * apart, or touching ones that show surfaces turned apart (foliage: leaves at random
     * angles, which a line crosses independently), blend as independent layers. Faithful
     * records keep the paper's rule: every voxel is a layer of its own. */
    int gx = x - c.s.px, gy = y - c.s.py, gz = z - c.s.pz;
    bool apart = gx < -1 || gx > 1 || gy < -1 || gy > 1 || gz < -1 || gz > 1;
    bool one_sheet = vx_app_walk_one_sheet(c.s.pnx, c.s.pny, c.s.pnz, seen.nx, seen.ny, seen.nz);
    if (c.s.w.visits == 0u || apart || !one_sheet || kind == VX_APP_KIND_FAITHFUL)
        c.s.run_t = c.s.w.transmittance, c.s.run_covered = 0.0f;
    float a = vx_fmin(seen.a, 1.0f - c.s.run_covered);
    c.s.w.r = vx_app_add_product(c.s.w.r, c.s.run_t, a, seen.r);
    c.s.w.g = vx_app_add_product(c.s.w.g, c.s.run_t, a, seen.g);
    c.s.w.b = vx_app_add_product(c.s.w.b, c.s.run_t, a, seen.b);
    c.s.w.nx = vx_app_add_product(c.s.w.nx, c.s.run_t, a, seen.nx);
    c.s.w.ny = vx_app_add_product(c.s.w.ny, c.s.run_t, a, seen.ny);
    c.s.w.nz = vx_app_add_product(c.s.w.nz, c.s.run_t, a, seen.nz);
    c.s.run_covered = c.s.run_covered + a;
    c.s.w.transmittance = c.s.run_t * (1.0f - c.s.run_covered);
    c.s.w.visits = c.s.w.visits + 1u;
    c.s.px = x, c.s.py = y, c.s.pz = z;
    c.s.pnx = seen.nx, c.s.pny = seen.ny, c.s.pnz = seen.nz;
    return c;
}

/* Where a re-entry starts once the ray left a voxel at exit_t: just past the exit (and not
 * before tmin), by c.nudge max(exit_t, 1). */
VX_FN float vx_app_walk_past(vx_app_walk_cursor c, float exit_t) {
    return vx_app_add_product(vx_fmax(c.r.tmin, exit_t), vx_fmax(exit_t, 1.0f), c.nudge, 1.0f);
}

/* The first half of a visit: takes closest hit `h` of c.r. Where it is a voxel with a
 * record, that is the voxel to blend (c.row, c.x, c.y, c.z); else the walk stops (going 0:
 * the ray left the structure, or the voxel has no record) or, where the re-entry landed in
 * the voxel just left, steps on and wants another closest hit. */
VX_FN vx_app_walk_cursor vx_app_walk_enter(VX_BLOB index, uint max_visits, vx_hit h, vx_app_walk_cursor c) {
    c.s.w.steps = c.s.w.steps + h.steps;
    c.tries = c.tries + 1u;
    c.going = 0u;
    c.row = VX_APP_NO_ROW;
    if (h.status != VX_STATUS_HIT) return c;
    if (c.s.w.visits > 0u && h.x == c.s.px && h.y == c.s.py && h.z == c.s.pz) {
        /* The re-entry landed in the voxel just left: at its far face the entry point's
         * rounding can keep a slow axis on this side. Step on, further each time. */
        c.r.tmin = vx_app_walk_past(c, vx_app_next_voxel(c.r, h.x, h.y, h.z).t);
        c.nudge = c.nudge * 4.0f;
        c.going = c.tries < 4u * max_visits ? 1u : 0u;
        return c;
    }
    c.nudge = 1.0e-6f;
    uint row = vx_app_row(index, h.x, h.y, h.z);
    if (row == VX_APP_NO_ROW) {
        c.s.w.status = VX_APP_WALK_NO_RECORD;
        c.s.w.x = h.x, c.s.w.y = h.y, c.s.w.z = h.z;
        return c;
    }
    if (c.s.w.visits == 0u) {
        c.s.w.t = h.t, c.s.w.x = h.x, c.s.w.y = h.y, c.s.w.z = h.z, c.s.w.face = h.face, c.s.w.material = h.material;
        c.s.w.status = VX_STATUS_HIT;
    }
    c.row = row, c.x = h.x, c.y = h.y, c.z = h.z, c.going = 1u;
    return c;
}

/* The second half: blends `seen`, what voxel c.row shows along the ray (vx_app_walk_sample),
 * and moves the ray past it. Where the ray goes straight on into a touching voxel that has a
 * record (a surface's voxels mostly touch), that one is the next to blend: one DDA step and a
 * lookup, not a re-entry. Where the ray leaves through an edge or a corner, or into a voxel
 * without a record, it re-enters just past the exit. The walk stops (going 0) when T fell
 * below `cutoff`, or the visits or closest hits ran out. */
VX_FN vx_app_walk_cursor vx_app_walk_take(VX_BLOB index, uint kind, float cutoff, uint max_visits,
                                          vx_app_sample seen, vx_app_walk_cursor c) {
    c = vx_app_walk_blend(seen, kind, c.x, c.y, c.z, c);
    c.row = VX_APP_NO_ROW;
    if (c.s.w.transmittance < cutoff) {
        c.going = 0u;
        return c;
    }
    vx_app_next next = vx_app_next_voxel(c.r, c.x, c.y, c.z);
    c.r.tmin = next.t;
    c.going = c.s.w.visits < max_visits && c.tries < 4u * max_visits ? 1u : 0u;
    if (c.going == 0u) return c;
    uint row = next.tie == 0u && next.t < c.r.tmax ? vx_app_row(index, next.x, next.y, next.z) : VX_APP_NO_ROW;
    if (row == VX_APP_NO_ROW) {
        /* Past the exit, by the step vx_app_walk_enter takes where a re-entry lands back in
         * the voxel it left: one at the exit itself did so in half the re-entries (the
         * entry point's rounding), each a closest hit for nothing. */
        c.r.tmin = vx_app_walk_past(c, next.t);
        return c;
    }
    c.s.w.steps = c.s.w.steps + 1u;
    c.row = row, c.x = next.x, c.y = next.y, c.z = next.z;
    return c;
}

/* The walk after the closest hit `h` of c.r: the voxel blended, then each voxel with a
 * record that the ray goes on into face to face, and the ray moved past the last of them
 * (vx_app_walk_enter, then vx_app_walk_take while there is a voxel to blend). It stops
 * (going 0) when the ray left the structure, T fell below `cutoff`, a voxel has no record,
 * or the visits or closest hits ran out. `shadows_at`: see vx_app_walk_light. */
VX_FN vx_app_walk_cursor vx_app_walk_visit(VX_BLOB index, VX_BLOB records, VX_BLOB faces, uint kind,
                                           vx_app_light light, float cutoff, uint max_visits, uint shadows_at,
                                           vx_hit h, vx_app_walk_cursor c) {
    c = vx_app_walk_enter(index, max_visits, h, c);
    while (c.row != VX_APP_NO_ROW)
        c = vx_app_walk_take(index, kind, cutoff, max_visits,
                             vx_app_walk_sample(records, faces, kind, light, shadows_at, c), c);
    return c;
}
