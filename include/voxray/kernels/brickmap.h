/* Traversal of the brickmap (layout/brickmap_layout.h): a nested DDA. The top walk steps
 * over top cells (the world scaled by 1/edge, which is exact, so its crossing t are bit for
 * bit those of the voxel walk at the same planes); at a non-empty cell it descends into a
 * voxel walk restricted to that cell (a brick, or a solid cell whose every voxel is solid),
 * and comes back up when the voxel walk leaves the cell. The hit voxel, t and face of a
 * solid cell are those of the voxel the ray enters: no "cell entry" shortcut.
 * Needs prelude.h, ray.h, dda.h. Included once per lane set; no include guard on purpose. */

VX_STRUCT(vx_brickmap)
    int ox, oy, oz;           /* world position of voxel (0,0,0) */
    int cells_x, cells_y, cells_z;
    uint pages_x, pages_xy;
    int brick_bits;           /* log2 of the brick edge */
    uint brick_words, occupancy_words;
    uint payload_bits, values_per_word_bits, payload_mask;
    uint page_table, pages, bricks;
VX_END_STRUCT(vx_brickmap)

VX_STRUCT(vx_bm_state)
    vx_dda top;               /* walk over top cells */
    vx_dda fine;              /* walk over the voxels of `cell` while level is 1 */
    vx_f32 dx, dy, dz;        /* the ray's direction, to find the entry voxel of a cell */
    vx_u32 cell;              /* value of the top cell being walked at voxel level */
    vx_u32 level;             /* 0: top cells, 1: voxels of `cell` */
    vx_u32 status;            /* VX_STATUS_* of the ray */
VX_END_STRUCT(vx_bm_state)

VX_FN vx_brickmap vx_bm_load(VX_BLOB blob) {
    vx_brickmap g;
    g.ox = vx_u2i(vx_load(blob, VX_BM_HEADER_ORIGIN + 0));
    g.oy = vx_u2i(vx_load(blob, VX_BM_HEADER_ORIGIN + 1));
    g.oz = vx_u2i(vx_load(blob, VX_BM_HEADER_ORIGIN + 2));
    g.cells_x = vx_u2i(vx_load(blob, VX_BM_HEADER_CELLS + 0));
    g.cells_y = vx_u2i(vx_load(blob, VX_BM_HEADER_CELLS + 1));
    g.cells_z = vx_u2i(vx_load(blob, VX_BM_HEADER_CELLS + 2));
    g.pages_x = vx_load(blob, VX_BM_HEADER_PAGES_DIM + 0);
    g.pages_xy = g.pages_x * vx_load(blob, VX_BM_HEADER_PAGES_DIM + 1);
    g.brick_bits = vx_u2i(vx_load(blob, VX_BM_HEADER_BRICK_BITS));
    g.brick_words = vx_load(blob, VX_BM_HEADER_BRICK_WORDS);
    g.occupancy_words = vx_load(blob, VX_BM_HEADER_OCCUPANCY_WORDS);
    g.payload_bits = vx_load(blob, VX_BM_HEADER_PAYLOAD_BITS);
    g.values_per_word_bits = g.payload_bits == 8u ? 2u : (g.payload_bits == 16u ? 1u : 0u);
    g.payload_mask = g.payload_bits == 32u ? 0xFFFFFFFFu : ((1u << g.payload_bits) - 1u);
    g.page_table = vx_load(blob, VX_BM_HEADER_PAGE_TABLE);
    g.pages = vx_load(blob, VX_BM_HEADER_PAGES);
    g.bricks = vx_load(blob, VX_BM_HEADER_BRICKS);
    return g;
}

/* Value of top cell c (0 = empty) for lanes in `live`, 0 elsewhere. */
VX_FN vx_u32 vx_bm_cell(VX_BLOB blob, vx_brickmap g, vx_i32 cx, vx_i32 cy, vx_i32 cz, vx_mask live) {
    vx_u32 slot = vx_i2u(cx >> VX_BM_PAGE_BITS) + vx_i2u(cy >> VX_BM_PAGE_BITS) * g.pages_x +
                  vx_i2u(cz >> VX_BM_PAGE_BITS) * g.pages_xy;
    vx_u32 page = vx_gather(blob, vx_sel(live, g.page_table + slot, 0u));
    vx_mask present = live && page != VX_BM_EMPTY_PAGE;
    vx_u32 index = vx_i2u((cx & VX_BM_PAGE_MASK) | ((cy & VX_BM_PAGE_MASK) << 4) | ((cz & VX_BM_PAGE_MASK) << 8));
    vx_u32 value = vx_sel(present, 0u, 0u);
    if (vx_any(present)) value = vx_gather(blob, vx_sel(present, g.pages + page * VX_BM_PAGE_WORDS + index, 0u));
    return vx_sel(present, value, 0u);
}

/* Index of voxel (x, y, z) inside its brick: lx | ly << b | lz << 2b. */
VX_FN vx_u32 vx_bm_voxel_bit(vx_brickmap g, vx_i32 x, vx_i32 y, vx_i32 z) {
    int m = (1 << g.brick_bits) - 1;
    return vx_i2u((x & m) | ((y & m) << g.brick_bits) | ((z & m) << (2 * g.brick_bits)));
}

/* Word offset of the brick a brick cell points to (lanes without a brick: 0). */
VX_FN vx_u32 vx_bm_brick(vx_brickmap g, vx_u32 cell) {
    return vx_sel((cell & VX_BM_CELL_IS_BRICK) != 0u, g.bricks + (cell >> 1u) * g.brick_words, 0u);
}

/* Starts the voxel walk inside the top cell the top walk is in (lanes in m). */
VX_FN vx_bm_state vx_bm_descend(vx_bm_state s, vx_brickmap g, vx_u32 cell, vx_mask m) {
    int edge = 1 << g.brick_bits;
    vx_i32 bx = s.top.cx << g.brick_bits, by = s.top.cy << g.brick_bits, bz = s.top.cz << g.brick_bits;
    vx_f32 t = s.top.t;
    /* The entry voxel: on the axis the cell was entered through it is the first slab;
     * on the others, the floor of the entry point clamped into the cell. */
    vx_f32 px = vx_sel(m, s.fine.ox + s.dx * t, 0.0f);
    vx_f32 py = vx_sel(m, s.fine.oy + s.dy * t, 0.0f);
    vx_f32 pz = vx_sel(m, s.fine.oz + s.dz * t, 0.0f);
    vx_i32 cx = vx_f2i(vx_floor(vx_fmin(vx_fmax(px - vx_i2f(bx), 0.0f), vx_i2f(edge - 1)))) + bx;
    vx_i32 cy = vx_f2i(vx_floor(vx_fmin(vx_fmax(py - vx_i2f(by), 0.0f), vx_i2f(edge - 1)))) + by;
    vx_i32 cz = vx_f2i(vx_floor(vx_fmin(vx_fmax(pz - vx_i2f(bz), 0.0f), vx_i2f(edge - 1)))) + bz;
    vx_u32 f = s.top.face;
    cx = vx_sel(f == VX_FACE_NEG_X, bx, vx_sel(f == VX_FACE_POS_X, bx + (edge - 1), cx));
    cy = vx_sel(f == VX_FACE_NEG_Y, by, vx_sel(f == VX_FACE_POS_Y, by + (edge - 1), cy));
    cz = vx_sel(f == VX_FACE_NEG_Z, bz, vx_sel(f == VX_FACE_POS_Z, bz + (edge - 1), cz));
    s.fine.cx = vx_sel(m, cx, s.fine.cx);
    s.fine.cy = vx_sel(m, cy, s.fine.cy);
    s.fine.cz = vx_sel(m, cz, s.fine.cz);
    s.fine.nx = vx_sel(m, vx_dda_exit_t(cx, s.fine.sx, s.fine.ox, s.fine.ix), s.fine.nx);
    s.fine.ny = vx_sel(m, vx_dda_exit_t(cy, s.fine.sy, s.fine.oy, s.fine.iy), s.fine.ny);
    s.fine.nz = vx_sel(m, vx_dda_exit_t(cz, s.fine.sz, s.fine.oz, s.fine.iz), s.fine.nz);
    s.fine.t = vx_sel(m, t, s.fine.t);
    s.fine.face = vx_sel(m, f, s.fine.face);
    s.fine.status = vx_sel(m, VX_STATUS_ACTIVE, s.fine.status);
    s.cell = vx_sel(m, cell, s.cell);
    s.level = vx_sel(m, 1u, s.level);
    return s;
}

VX_FN vx_bm_state vx_bm_begin(vx_brickmap g, vx_ray r) {
    vx_bm_state s;
    float edge = vx_i2f(1 << g.brick_bits);
    s.top = vx_dda_begin_scaled(r, vx_i2f(g.ox), vx_i2f(g.oy), vx_i2f(g.oz), g.cells_x, g.cells_y, g.cells_z, edge);
    /* Only the voxel walk's origin, 1/direction and steps are used until a descent. */
    s.fine = vx_dda_begin_scaled(r, vx_i2f(g.ox), vx_i2f(g.oy), vx_i2f(g.oz), g.cells_x << g.brick_bits,
                                 g.cells_y << g.brick_bits, g.cells_z << g.brick_bits, 1.0f);
    s.fine.steps = s.top.steps;
    s.dx = r.dx;
    s.dy = r.dy;
    s.dz = r.dz;
    s.cell = vx_sel(s.top.status == VX_STATUS_ACTIVE, 0u, 0u);
    s.level = s.cell;
    s.status = s.top.status;
    return s;
}

/* One step: at top level, descend into a non-empty cell or move to the next cell; at
 * voxel level, a hit if the voxel is solid, else move on, back to the top walk when the
 * voxel walk leaves the cell. */
VX_FN vx_bm_state vx_bm_step(VX_BLOB blob, vx_brickmap g, vx_bm_state s) {
    vx_mask live = s.status == VX_STATUS_ACTIVE;
    vx_mask at_top = live && s.level == 0u;
    vx_mask at_voxel = live && s.level == 1u;

    if (vx_any(at_top)) {
        vx_u32 cell = vx_bm_cell(blob, g, s.top.cx, s.top.cy, s.top.cz, at_top);
        vx_mask enter = at_top && cell != VX_BM_CELL_EMPTY;
        vx_mask pass = at_top && !enter;
        /* Guards on vx_any keep SIMD lanes from paying for work no lane needs. */
        if (vx_any(enter)) s = vx_bm_descend(s, g, cell, enter);
        if (vx_any(pass)) {
            s.top = vx_dda_advance(s.top, pass, g.cells_x, g.cells_y, g.cells_z);
            s.status = vx_sel(pass, s.top.status, s.status);
        }
    }
    if (vx_any(at_voxel)) {
        vx_u32 brick = vx_bm_brick(g, s.cell);
        vx_mask in_brick = at_voxel && brick != 0u;
        vx_u32 bit = vx_bm_voxel_bit(g, s.fine.cx, s.fine.cy, s.fine.cz);
        vx_u32 word = vx_gather(blob, vx_sel(in_brick, brick + (bit >> 5u), 0u));
        vx_mask solid = at_voxel && (!in_brick || ((word >> (bit & 31u)) & 1u) != 0u);
        s.status = vx_sel(solid, VX_STATUS_HIT, s.status);

        vx_mask go = at_voxel && !solid;
        s.fine = vx_dda_move(s.fine, go);
        vx_mask ended = go && s.fine.status == VX_STATUS_MISS;  /* passed tmax */
        s.status = vx_sel(ended, VX_STATUS_MISS, s.status);
        vx_mask leaves = go && !ended &&
                         ((s.fine.cx >> g.brick_bits) != s.top.cx || (s.fine.cy >> g.brick_bits) != s.top.cy ||
                          (s.fine.cz >> g.brick_bits) != s.top.cz);
        /* Back to the top walk: its next crossing is the one the voxel walk just made. */
        if (vx_any(leaves)) {
            s.level = vx_sel(leaves, 0u, s.level);
            s.top = vx_dda_advance(s.top, leaves, g.cells_x, g.cells_y, g.cells_z);
            s.status = vx_sel(leaves, s.top.status, s.status);
        }
    }
    return s;
}

VX_FN vx_hit vx_bm_finish(VX_BLOB blob, vx_brickmap g, vx_bm_state s) {
    vx_hit h;
    vx_mask is_hit = s.status == VX_STATUS_HIT;
    vx_u32 brick = vx_bm_brick(g, vx_sel(is_hit, s.cell, 0u));
    vx_mask in_brick = is_hit && brick != 0u;
    vx_u32 bit = vx_bm_voxel_bit(g, s.fine.cx, s.fine.cy, s.fine.cz);
    vx_u32 word = vx_gather(blob, vx_sel(in_brick, brick + g.occupancy_words + (bit >> g.values_per_word_bits), 0u));
    vx_u32 shift = (bit & ((1u << g.values_per_word_bits) - 1u)) * g.payload_bits;
    vx_u32 payload = vx_sel(in_brick, (word >> shift) & g.payload_mask, s.cell >> 1u);
    h.t = vx_sel(is_hit, s.fine.t, VX_INF);
    h.x = vx_sel(is_hit, s.fine.cx + g.ox, 0);
    h.y = vx_sel(is_hit, s.fine.cy + g.oy, 0);
    h.z = vx_sel(is_hit, s.fine.cz + g.oz, 0);
    h.face = vx_sel(is_hit, s.fine.face, VX_FACE_NONE);
    h.material = vx_sel(is_hit, payload, 0u);
    h.steps = s.top.steps + s.fine.steps;
    h.status = s.status;
    return h;
}

/* Per lane: a where m is set, else b (the CPU stream's lane refill). */
VX_FN vx_bm_state vx_bm_select(vx_mask m, vx_bm_state a, vx_bm_state b) {
    vx_bm_state s;
    s.top = vx_dda_select(m, a.top, b.top);
    s.fine = vx_dda_select(m, a.fine, b.fine);
    s.dx = vx_sel(m, a.dx, b.dx);
    s.dy = vx_sel(m, a.dy, b.dy);
    s.dz = vx_sel(m, a.dz, b.dz);
    s.cell = vx_sel(m, a.cell, b.cell);
    s.level = vx_sel(m, a.level, b.level);
    s.status = vx_sel(m, a.status, b.status);
    return s;
}

/* Closest hit; the first solid voxel is also a valid any-hit answer. */
VX_FN vx_hit vx_brickmap_trace(VX_BLOB blob, vx_ray r, uint mode) {
    VX_UNUSED(mode);
    vx_brickmap g = vx_bm_load(blob);
    vx_bm_state s = vx_bm_begin(g, r);
    while (vx_any(s.status == VX_STATUS_ACTIVE)) s = vx_bm_step(blob, g, s);
    return vx_bm_finish(blob, g, s);
}
