/* Exact grid DDA over cells [0, extent) on each axis, one cell a step.
 *
 * Robustness (why it is written this way):
 *  - the crossing t of every cell boundary is computed from the integer cell index
 *    ((c + 1 - o) / d), never accumulated, so no error grows with the number of steps;
 *  - the entry cell is clamped into the grid, and on the axis the ray enters through it is
 *    set exactly (first or last slab), so float rounding at the box never loses a ray;
 *  - axes with a zero direction never step (their crossing t is +inf) and no division by
 *    zero reaches a result: GLSL leaves x/0 undefined;
 *  - rays with NaN/Inf in origin, direction or tmin, NaN tmax, a zero (or denormal) direction or
 *    tmin > tmax are misses. tmax = +inf is fine;
 *  - a walk whose entry or next crossing t overflows float (far origins, tiny components)
 *    misses: t = inf cannot say where a hit is, and every crossing would tie at inf.
 * Axes that reach a boundary at the same t step together (see vx_dda_advance).
 * Per-lane code has no branches: it runs unchanged on SIMD lanes. */

VX_STRUCT(vx_dda)
    vx_f32 ox, oy, oz;   /* ray origin relative to the grid's min corner */
    vx_f32 ix, iy, iz;   /* 1 / direction, 0 where the direction is 0 */
    vx_i32 sx, sy, sz;   /* step per axis: -1, 0 or +1 */
    vx_i32 cx, cy, cz;   /* current cell */
    vx_f32 nx, ny, nz;   /* t at which the ray leaves the current cell, per axis */
    vx_f32 t;            /* t at which the ray entered the current cell */
    vx_f32 tmax;         /* the ray's tmax */
    vx_u32 face;         /* VX_FACE_* the current cell was entered through */
    vx_u32 status;       /* VX_STATUS_* */
    vx_u32 steps;        /* cells left behind so far */
VX_END_STRUCT(vx_dda)

/* One axis of the ray/box slab test. */
VX_STRUCT(vx_slab)
    vx_f32 inv, t0, t1;
    vx_i32 step;
VX_END_STRUCT(vx_slab)

/* An axis moves when |d| >= 2^-120: then 1/d, even scaled by a cell size of up to 16
 * (vx_dda_begin_scaled), is finite, so no crossing t is ever NaN (inf * 0), and every step
 * moves at least one axis: the walk ends after at most ex + ey + ez steps, with no iteration
 * cap. Smaller components (denormals included) count as zero, identically on devices that
 * flush denormals and on those that do not. */
#define VX_MIN_DIRECTION 7.52316385e-37f
#define vx_moves(d) ((d) >= VX_MIN_DIRECTION || (d) <= -VX_MIN_DIRECTION)

/* `o` is already in cell units; `cell` scales 1/d into them (exact: a power of two). */
VX_FN vx_slab vx_slab_make(vx_f32 o, vx_f32 d, float extent, float cell) {
    vx_slab s;
    vx_mask moving = vx_moves(d);
    s.inv = vx_sel(moving, (1.0f / vx_sel(moving, d, 1.0f)) * cell, 0.0f);
    s.step = vx_sel(moving, vx_sel(d > 0.0f, 1, -1), 0);
    vx_f32 ta = (0.0f - o) * s.inv;
    vx_f32 tb = (extent - o) * s.inv;
    vx_mask inside = o >= 0.0f && o < extent;
    s.t0 = vx_sel(moving, vx_fmin(ta, tb), vx_sel(inside, -VX_INF, VX_INF));
    s.t1 = vx_sel(moving, vx_fmax(ta, tb), vx_sel(inside, VX_INF, -VX_INF));
    return s;
}

/* Start cell along one axis: floor of the entry point, clamped into [0, extent). */
VX_FN vx_i32 vx_dda_start_cell(vx_f32 p, int extent) {
    vx_f32 q = vx_fmin(vx_fmax(p, 0.0f), vx_i2f(extent - 1));
    return vx_f2i(vx_floor(q));
}

/* t at which the ray leaves, along one axis, the cell of `size` voxels whose min voxel
 * is c (the brickmap walks cells of several sizes in voxel units). */
VX_FN vx_f32 vx_dda_exit_t_sized(vx_i32 c, vx_i32 size, vx_i32 step, vx_f32 o, vx_f32 inv) {
    return vx_sel(step != 0, (vx_i2f(c + vx_sel(step > 0, size, 0)) - o) * inv, VX_INF);
}

/* t at which the ray leaves cell c along one axis. */
VX_FN vx_f32 vx_dda_exit_t(vx_i32 c, vx_i32 step, vx_f32 o, vx_f32 inv) {
    return vx_sel(step != 0, (vx_i2f(c + ((step + 1) >> 1)) - o) * inv, VX_INF);
}

/* Sets up the walk of ray r (in world units) through a grid whose cell (0,0,0) has its
 * min corner at world position (gx, gy, gz), that has (ex, ey, ez) cells, each `cell`
 * voxels wide (a power of two). Scaling by a power of two is exact, so a walk over coarse
 * cells computes bit for bit the same t at a plane as a walk over voxels does. */
VX_FN vx_dda vx_dda_begin_scaled(vx_ray r, float gx, float gy, float gz, int ex, int ey, int ez, float cell) {
    vx_dda d;
    float to_cells = 1.0f / cell;
    d.ox = (r.ox - gx) * to_cells;
    d.oy = (r.oy - gy) * to_cells;
    d.oz = (r.oz - gz) * to_cells;
    vx_mask valid = vx_is_finite(r.ox) && vx_is_finite(r.oy) && vx_is_finite(r.oz) &&
                    vx_is_finite(r.dx) && vx_is_finite(r.dy) && vx_is_finite(r.dz) &&
                    vx_is_finite(r.tmin) && !vx_is_nan(r.tmax) && r.tmin <= r.tmax &&
                    (vx_moves(r.dx) || vx_moves(r.dy) || vx_moves(r.dz)) && ex > 0 && ey > 0 && ez > 0;
    vx_slab sx = vx_slab_make(d.ox, r.dx, vx_i2f(ex), cell);
    vx_slab sy = vx_slab_make(d.oy, r.dy, vx_i2f(ey), cell);
    vx_slab sz = vx_slab_make(d.oz, r.dz, vx_i2f(ez), cell);
    d.ix = sx.inv; d.iy = sy.inv; d.iz = sz.inv;
    d.sx = sx.step; d.sy = sy.step; d.sz = sz.step;

    vx_f32 tbox = vx_fmax(sx.t0, vx_fmax(sy.t0, sz.t0));
    vx_f32 tenter = vx_fmax(r.tmin, tbox);
    vx_f32 texit = vx_fmin(r.tmax, vx_fmin(sx.t1, vx_fmin(sy.t1, sz.t1)));
    /* An entry beyond the float range (a far origin, a tiny direction) is no hit: t = inf
     * cannot say where, and the walk could not order its crossings. */
    valid = valid && tenter <= texit && vx_is_finite(tenter);

    /* Entered through a box face (not started inside): which one, x before y before z. */
    vx_mask through_face = tbox >= r.tmin;
    vx_mask ax = through_face && sx.t0 == tbox;
    vx_mask ay = through_face && !ax && sy.t0 == tbox;
    vx_mask az = through_face && !ax && !ay;

    /* The entry point; a component that counts as zero is zero here too (the slab test
     * above already treats it so), or a huge t would carry the point off its cell. */
    vx_f32 tp = vx_sel(valid, tenter, 0.0f);
    vx_f32 px = vx_sel(valid, d.ox + vx_sel(sx.step != 0, r.dx, 0.0f) * to_cells * tp, 0.0f);
    vx_f32 py = vx_sel(valid, d.oy + vx_sel(sy.step != 0, r.dy, 0.0f) * to_cells * tp, 0.0f);
    vx_f32 pz = vx_sel(valid, d.oz + vx_sel(sz.step != 0, r.dz, 0.0f) * to_cells * tp, 0.0f);
    /* A ray whose span in the box has zero length (it starts on the box's far side, or only
     * touches an edge or corner) meets a voxel only if that point lies in one: cells are
     * half-open, so a point on a max face lies outside. Off the entry axis the point must
     * be inside; on it, it is on the face by construction. */
    vx_mask touch = tenter == texit;
    vx_mask point_inside = (ax || (px >= 0.0f && px < vx_i2f(ex))) && (ay || (py >= 0.0f && py < vx_i2f(ey))) &&
                           (az || (pz >= 0.0f && pz < vx_i2f(ez)));
    valid = valid && (!touch || point_inside);
    d.cx = vx_sel(ax, vx_sel(d.sx > 0, 0, ex - 1), vx_dda_start_cell(px, ex));
    d.cy = vx_sel(ay, vx_sel(d.sy > 0, 0, ey - 1), vx_dda_start_cell(py, ey));
    d.cz = vx_sel(az, vx_sel(d.sz > 0, 0, ez - 1), vx_dda_start_cell(pz, ez));
    d.nx = vx_dda_exit_t(d.cx, d.sx, d.ox, d.ix);
    d.ny = vx_dda_exit_t(d.cy, d.sy, d.oy, d.iy);
    d.nz = vx_dda_exit_t(d.cz, d.sz, d.oz, d.iz);

    d.face = vx_sel(ax, vx_sel(d.sx > 0, VX_FACE_NEG_X, VX_FACE_POS_X),
             vx_sel(ay, vx_sel(d.sy > 0, VX_FACE_NEG_Y, VX_FACE_POS_Y),
             vx_sel(az, vx_sel(d.sz > 0, VX_FACE_NEG_Z, VX_FACE_POS_Z), VX_FACE_INSIDE)));
    d.t = tenter;
    d.tmax = r.tmax;
    d.status = vx_sel(valid, VX_STATUS_ACTIVE, VX_STATUS_MISS);
    d.steps = vx_u32_splat(0u);
    return d;
}

/* Moves lanes in `go` to the next cell, `size` voxels on (1 for a plain grid walk);
 * those that pass tmax miss. Every axis whose boundary lies at the nearest t steps at
 * once: a ray through an edge or corner goes straight to the diagonal cell instead of
 * visiting side cells for zero length (which would report hits on voxels the ray only
 * touches). */
VX_FN vx_dda vx_dda_move_sized(vx_dda d, vx_mask go, vx_i32 size) {
    vx_f32 tnext = vx_fmin(d.nx, vx_fmin(d.ny, d.nz));
    vx_mask mx = go && d.nx == tnext;
    vx_mask my = go && d.ny == tnext;
    vx_mask mz = go && d.nz == tnext;

    d.cx = vx_sel(mx, d.cx + d.sx * size, d.cx);
    d.cy = vx_sel(my, d.cy + d.sy * size, d.cy);
    d.cz = vx_sel(mz, d.cz + d.sz * size, d.cz);
    d.nx = vx_sel(mx, vx_dda_exit_t_sized(d.cx, size, d.sx, d.ox, d.ix), d.nx);
    d.ny = vx_sel(my, vx_dda_exit_t_sized(d.cy, size, d.sy, d.oy, d.iy), d.ny);
    d.nz = vx_sel(mz, vx_dda_exit_t_sized(d.cz, size, d.sz, d.oz, d.iz), d.nz);
    /* On an edge or corner the entry face is a tie; report the first stepped axis. */
    d.face = vx_sel(mx, vx_sel(d.sx > 0, VX_FACE_NEG_X, VX_FACE_POS_X),
             vx_sel(my, vx_sel(d.sy > 0, VX_FACE_NEG_Y, VX_FACE_POS_Y),
             vx_sel(mz, vx_sel(d.sz > 0, VX_FACE_NEG_Z, VX_FACE_POS_Z), d.face)));
    /* Past tmax, or past the float range (every crossing then ties at inf), is a miss. */
    d.status = vx_sel(go && (tnext > d.tmax || !vx_is_finite(tnext)), VX_STATUS_MISS, d.status);
    d.t = vx_sel(go, vx_fmax(d.t, tnext), d.t);
    d.steps = d.steps + vx_sel(go, 1u, 0u);
    return d;
}

/* vx_dda_move_sized over unit cells. */
VX_FN vx_dda vx_dda_move(vx_dda d, vx_mask go) { return vx_dda_move_sized(d, go, vx_i32_splat(1)); }

/* vx_dda_move, and lanes that leave the grid [0, e) miss. */
VX_FN vx_dda vx_dda_advance(vx_dda d, vx_mask go, int ex, int ey, int ez) {
    d = vx_dda_move(d, go);
    vx_mask leaves = d.cx < 0 || d.cy < 0 || d.cz < 0 || d.cx >= ex || d.cy >= ey || d.cz >= ez;
    d.status = vx_sel(go && leaves, VX_STATUS_MISS, d.status);
    return d;
}

/* t at which the ray enters cell l (cells of `size` voxels from voxel `base`) along one
 * axis: the plane it crosses to get there, computed as every crossing is. */
VX_FN vx_f32 vx_dda_entry_t(vx_i32 base, vx_i32 l, vx_i32 size, vx_i32 step, vx_f32 o, vx_f32 inv) {
    return (vx_i2f(base + (l + vx_sel(step < 0, 1, 0)) * size) - o) * inv;
}

/* The cell (as above) the walk is in at parameter t along one axis, from an estimate that
 * rounding may have put one cell off. A moving walk has entered a cell once its plane's
 * crossing t is <= t, ties included (vx_dda_move steps tied axes together), so a
 * structure that jumps to the cell at t lands exactly where the reference walk over
 * voxels is. A non-moving axis keeps the estimate. */
VX_FN vx_i32 vx_dda_cell_at(vx_i32 estimate, vx_i32 base, vx_i32 size, vx_i32 step, vx_f32 o, vx_f32 inv, vx_f32 t) {
    vx_i32 c = vx_sel(step != 0 && vx_dda_entry_t(base, estimate, size, step, o, inv) > t, estimate - step, estimate);
    return vx_sel(step != 0 && vx_dda_entry_t(base, c + step, size, step, o, inv) <= t, c + step, c);
}

/* One axis of vx_dda_reenter: the index, in cells of `sub` voxels, of the sub-cell of the
 * cell [c, c + n * sub) where the walk is at parameter t: the floor of the point at t, and
 * where the cell was entered by a move, corrected to the crossing rule (vx_dda_cell_at),
 * which also puts the axis the cell was entered through on its first (or last) slab
 * exactly. In the cell the walk began in (`start`: no move yet) the floor stays, the
 * half-open rule vx_dda_begin_scaled applies to the ray's first cell. Power-of-two sizes keep the scaling exact. */
VX_FN vx_i32 vx_dda_reenter_axis(vx_f32 o, vx_f32 dir, vx_f32 inv, vx_i32 step, vx_f32 t, vx_i32 c, vx_i32 sub,
                                 vx_i32 n, vx_mask start) {
    vx_f32 p = (o + dir * t - vx_i2f(c)) / vx_i2f(sub);
    vx_i32 l = vx_f2i(vx_floor(vx_fmin(vx_fmax(p, 0.0f), vx_i2f(n - 1))));
    l = vx_sel(start, l, vx_dda_cell_at(l, c, sub, step, o, inv, t));
    return vx_sel(l < 0, 0, vx_sel(l >= n, n - 1, l));
}

/* Shared walk primitive: continue the walk, in lanes m, one level down inside the cell it
 * is in (min voxel d.c, `size` voxels wide), in sub-cells of `sub` voxels, starting at the
 * sub-cell where the ray entered the cell (at d.t). (dx, dy, dz) is the ray direction.
 * Every crossing t stays (plane - o) / d in voxel units, so a structure that descends
 * (brickmap, NAADF, a DAG's octants) meets the same planes, bit for bit, as the reference
 * walk over voxels, and reports the same face: the first axis, x before y before z, whose
 * plane the ray crossed at d.t, interior planes of the cell included. */
VX_FN vx_dda vx_dda_reenter(vx_dda d, vx_f32 dx, vx_f32 dy, vx_f32 dz, vx_i32 size, vx_i32 sub, vx_mask m) {
    vx_f32 t = vx_sel(m, d.t, 0.0f);
    vx_i32 n = vx_sel(m, size / sub, 1);
    vx_mask start = d.steps == 0u; /* still in the cell vx_dda_begin_scaled chose */
    /* A component that counts as zero (vx_moves) moves nothing, even over a huge t. */
    vx_i32 lx = vx_dda_reenter_axis(d.ox, vx_sel(m && d.sx != 0, dx, 0.0f), d.ix, d.sx, t, d.cx, sub, n, start);
    vx_i32 ly = vx_dda_reenter_axis(d.oy, vx_sel(m && d.sy != 0, dy, 0.0f), d.iy, d.sy, t, d.cy, sub, n, start);
    vx_i32 lz = vx_dda_reenter_axis(d.oz, vx_sel(m && d.sz != 0, dz, 0.0f), d.iz, d.sz, t, d.cz, sub, n, start);
    vx_mask fx = m && !start && d.sx != 0 && vx_dda_entry_t(d.cx, lx, sub, d.sx, d.ox, d.ix) == t;
    vx_mask fy = m && !start && d.sy != 0 && vx_dda_entry_t(d.cy, ly, sub, d.sy, d.oy, d.iy) == t;
    vx_mask fz = m && !start && d.sz != 0 && vx_dda_entry_t(d.cz, lz, sub, d.sz, d.oz, d.iz) == t;
    d.face = vx_sel(fx, vx_sel(d.sx > 0, VX_FACE_NEG_X, VX_FACE_POS_X),
             vx_sel(fy, vx_sel(d.sy > 0, VX_FACE_NEG_Y, VX_FACE_POS_Y),
             vx_sel(fz, vx_sel(d.sz > 0, VX_FACE_NEG_Z, VX_FACE_POS_Z), d.face)));
    d.cx = vx_sel(m, d.cx + lx * sub, d.cx);
    d.cy = vx_sel(m, d.cy + ly * sub, d.cy);
    d.cz = vx_sel(m, d.cz + lz * sub, d.cz);
    d.nx = vx_sel(m, vx_dda_exit_t_sized(d.cx, sub, d.sx, d.ox, d.ix), d.nx);
    d.ny = vx_sel(m, vx_dda_exit_t_sized(d.cy, sub, d.sy, d.oy, d.iy), d.ny);
    d.nz = vx_sel(m, vx_dda_exit_t_sized(d.cz, sub, d.sz, d.oz, d.iz), d.nz);
    return d;
}

/* One axis of vx_dda_leave_box: the cell past the box on an exit axis, else the cell the
 * walk is in at t (clamped into the box, which the ray is inside of on that axis). */
VX_FN vx_i32 vx_dda_leave_axis(vx_mask exits, vx_i32 lo, vx_i32 hi, vx_i32 step, vx_f32 o, vx_f32 dir, vx_f32 inv,
                               vx_f32 t, vx_i32 current) {
    vx_i32 estimate = vx_f2i(vx_floor(vx_fmin(vx_fmax(o + dir * t, vx_i2f(lo)), vx_i2f(hi - 1))));
    vx_i32 c = vx_dda_cell_at(estimate, vx_i32_splat(0), vx_i32_splat(1), step, o, inv, t);
    c = vx_sel(c < lo, lo, vx_sel(c >= hi, hi - 1, c));
    /* Never back against the step (a walk only moves forward, as the reference's does):
     * with every axis monotone and the exit axes strictly past the box, the walk ends even
     * where rounding at huge t puts the cell at t behind the walk. */
    c = vx_sel(step > 0 && c < current, current, vx_sel(step < 0 && c > current, current, c));
    return vx_sel(exits, vx_sel(step > 0, hi, lo - 1), c);
}

/* Whether the walk stepped along this axis at t, into cell c from `from` (the reported
 * face is the first such axis, x before y before z, as in vx_dda_move_sized). */
VX_FN vx_mask vx_dda_stepped_at(vx_i32 c, vx_i32 from, vx_i32 step, vx_f32 o, vx_f32 inv, vx_f32 t) {
    return step != 0 && c != from && vx_dda_entry_t(vx_i32_splat(0), c, vx_i32_splat(1), step, o, inv) == t;
}

/* Shared walk primitive: in lanes m, leave the empty box [lo, hi) (voxels; the walk is
 * inside it) in one move, to the voxel just past its exit face; every axis whose plane
 * lies at the exit t steps (edges and corners, as in vx_dda_move_sized). The walk is
 * then at voxel level (cell size 1); lanes past tmax miss. Leaving the grid is the
 * caller's test. The cell, t, face and next crossings are exactly those the reference
 * walk over voxels reaches (tests/cpu/test_walk_primitives.cpp checks it). */
VX_FN vx_dda vx_dda_leave_box(vx_dda d, vx_f32 dx, vx_f32 dy, vx_f32 dz, vx_i32 lox, vx_i32 loy, vx_i32 loz,
                              vx_i32 hix, vx_i32 hiy, vx_i32 hiz, vx_mask m) {
    vx_f32 ex = vx_dda_exit_t_sized(lox, hix - lox, d.sx, d.ox, d.ix);
    vx_f32 ey = vx_dda_exit_t_sized(loy, hiy - loy, d.sy, d.oy, d.iy);
    vx_f32 ez = vx_dda_exit_t_sized(loz, hiz - loz, d.sz, d.oz, d.iz);
    vx_f32 texit = vx_fmin(ex, vx_fmin(ey, ez));
    vx_mask mx = m && ex == texit, my = m && ey == texit, mz = m && ez == texit;
    /* Where the walk is once out: at texit, or still at d.t where the box's exit plane was
     * crossed before the walk's current t (a ray that entered the world on that plane:
     * the reference then steps that axis at d.t too, as vx_dda_move_sized does). */
    vx_f32 t = vx_sel(m, vx_fmax(d.t, texit), 0.0f);
    vx_i32 fx = d.cx, fy = d.cy, fz = d.cz;
    /* A component that counts as zero (vx_moves) moves nothing, even over a huge t. */
    d.cx = vx_sel(m, vx_dda_leave_axis(mx, lox, hix, d.sx, d.ox, vx_sel(d.sx != 0, dx, 0.0f), d.ix, t, d.cx), d.cx);
    d.cy = vx_sel(m, vx_dda_leave_axis(my, loy, hiy, d.sy, d.oy, vx_sel(d.sy != 0, dy, 0.0f), d.iy, t, d.cy), d.cy);
    d.cz = vx_sel(m, vx_dda_leave_axis(mz, loz, hiz, d.sz, d.oz, vx_sel(d.sz != 0, dz, 0.0f), d.iz, t, d.cz), d.cz);
    /* Interior planes crossed at the exit t step too, and may name the face. */
    mx = m && (mx || vx_dda_stepped_at(d.cx, fx, d.sx, d.ox, d.ix, t));
    my = m && (my || vx_dda_stepped_at(d.cy, fy, d.sy, d.oy, d.iy, t));
    mz = m && (mz || vx_dda_stepped_at(d.cz, fz, d.sz, d.oz, d.iz, t));
    d.nx = vx_sel(m, vx_dda_exit_t(d.cx, d.sx, d.ox, d.ix), d.nx);
    d.ny = vx_sel(m, vx_dda_exit_t(d.cy, d.sy, d.oy, d.iy), d.ny);
    d.nz = vx_sel(m, vx_dda_exit_t(d.cz, d.sz, d.oz, d.iz), d.nz);
    d.face = vx_sel(mx, vx_sel(d.sx > 0, VX_FACE_NEG_X, VX_FACE_POS_X),
             vx_sel(my, vx_sel(d.sy > 0, VX_FACE_NEG_Y, VX_FACE_POS_Y),
             vx_sel(mz, vx_sel(d.sz > 0, VX_FACE_NEG_Z, VX_FACE_POS_Z), d.face)));
    d.status = vx_sel(m && (texit > d.tmax || !vx_is_finite(texit)), VX_STATUS_MISS, d.status);
    d.t = vx_sel(m, vx_fmax(d.t, texit), d.t);
    d.steps = d.steps + vx_sel(m, 1u, 0u);
    return d;
}

/* The hit record of a walk that ended (hit, miss or past tmax): t, voxel (world position:
 * walk cell plus the world position (ox, oy, oz) of walk cell 0), face and material where
 * it hit, the step count and status always. Every structure's kernel ends with it. */
VX_FN vx_hit vx_hit_from_walk(vx_dda d, int ox, int oy, int oz, vx_u32 material) {
    vx_hit h;
    vx_mask is_hit = d.status == VX_STATUS_HIT;
    h.t = vx_sel(is_hit, d.t, VX_INF);
    h.x = vx_sel(is_hit, d.cx + ox, 0);
    h.y = vx_sel(is_hit, d.cy + oy, 0);
    h.z = vx_sel(is_hit, d.cz + oz, 0);
    h.face = vx_sel(is_hit, d.face, VX_FACE_NONE);
    h.material = vx_sel(is_hit, material, 0u);
    h.steps = d.steps;
    h.status = d.status;
    return h;
}
