/* Traversal of the brickmap (brickmap/layout.h): a nested DDA written as ONE walk
 * whose cell size changes. At top level a cell is a whole top cell (brick edge wide,
 * aligned); at a non-empty one the walk descends and steps voxel by voxel; when it leaves
 * that top cell it ascends again. All cell boundaries are voxel planes, so every crossing
 * t is computed exactly as the reference grid computes it: (plane - o) / d in voxel units.
 * One walk (not a top walk plus a voxel walk) keeps the state small and gives SIMD lanes
 * one move per step whatever level each lane is at. The hit voxel, t and face of a solid
 * cell are those of the voxel the ray enters: no "cell entry" shortcut.
 * Needs prelude.h, ray.h, dda.h. Included once per lane set; no include guard on purpose. */
#include "voxray/brickmap/layout.h"
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
    vx_dda w;            /* the walk, in voxel units; w.c is the min voxel of the current
                            cell: a whole top cell (aligned) or a single voxel */
    vx_f32 dx, dy, dz;   /* direction, to find the voxel where a top cell is entered */
    vx_u32 cell;         /* the top cell's value while walking its voxels; 0 at top level */
VX_END_STRUCT(vx_bm_state)

VX_FN vx_brickmap vx_brickmap_load(VX_BLOB blob) {
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
    vx_u32 slot = VX_BM_PAGE_SLOT(vx_i2u(cx), vx_i2u(cy), vx_i2u(cz), g.pages_x, g.pages_xy);
    vx_u32 page = vx_gather(blob, vx_sel(live, g.page_table + slot, 0u));
    vx_mask present = live && page != VX_BM_EMPTY_PAGE;
    vx_u32 index = vx_i2u(VX_BM_PAGE_CELL(cx, cy, cz));
    return vx_gather_masked(blob, present, g.pages + page * VX_BM_PAGE_WORDS + index);
}

/* Index of voxel (x, y, z) inside its brick: lx | ly << b | lz << 2b. */
VX_FN vx_u32 vx_bm_voxel_bit(vx_brickmap g, vx_i32 x, vx_i32 y, vx_i32 z) {
    int m = (1 << g.brick_bits) - 1;
    return vx_i2u(VX_BM_VOXEL_INDEX(x & m, y & m, z & m, g.brick_bits));
}

/* Word offset of the brick a brick cell points to (lanes without a brick: 0). */
VX_FN vx_u32 vx_bm_brick(vx_brickmap g, vx_u32 cell) {
    return vx_sel((cell & VX_BM_CELL_IS_BRICK) != 0u, g.bricks + VX_BM_CELL_VALUE(cell) * g.brick_words, 0u);
}

VX_FN vx_bm_state vx_brickmap_begin(vx_brickmap g, vx_ray r) {
    vx_bm_state s;
    int edge = 1 << g.brick_bits;
    /* Start with the grid DDA over top cells (in scaled units, which are exact), then
     * express it in voxel units: same t, origin and 1/direction scaled back. */
    s.w = vx_dda_begin_scaled(r, vx_i2f(g.ox), vx_i2f(g.oy), vx_i2f(g.oz), g.cells_x, g.cells_y, g.cells_z,
                              vx_i2f(edge));
    float to_voxels = vx_i2f(edge), to_inverse = 1.0f / vx_i2f(edge);
    s.w.ox = s.w.ox * to_voxels; s.w.oy = s.w.oy * to_voxels; s.w.oz = s.w.oz * to_voxels;
    s.w.ix = s.w.ix * to_inverse; s.w.iy = s.w.iy * to_inverse; s.w.iz = s.w.iz * to_inverse;
    s.w.cx = s.w.cx << g.brick_bits; s.w.cy = s.w.cy << g.brick_bits; s.w.cz = s.w.cz << g.brick_bits;
    s.dx = r.dx; s.dy = r.dy; s.dz = r.dz;
    s.cell = vx_u32_splat(0u);
    return s;
}

/* Descends into the top cell the walk is in (lanes in m; its value is `cell`): the walk
 * continues at the voxel where the ray entered it (vx_dda_reenter). */
VX_FN vx_bm_state vx_bm_descend(vx_bm_state s, vx_brickmap g, vx_u32 cell, vx_mask m) {
    s.w = vx_dda_reenter(s.w, s.dx, s.dy, s.dz, vx_i32_splat(1 << g.brick_bits), vx_i32_splat(1), m);
    s.cell = vx_sel(m, cell, s.cell);
    return s;
}

/* Back to the top level for lanes in m: the top cell holding the current voxel. Leaving
 * the map is a miss. */
VX_FN vx_bm_state vx_bm_ascend(vx_bm_state s, vx_brickmap g, vx_mask m) {
    int edge = 1 << g.brick_bits;
    vx_i32 tx = s.w.cx >> g.brick_bits, ty = s.w.cy >> g.brick_bits, tz = s.w.cz >> g.brick_bits;
    vx_mask outside = tx < 0 || ty < 0 || tz < 0 || tx >= g.cells_x || ty >= g.cells_y || tz >= g.cells_z;
    s.w.cx = vx_sel(m, tx << g.brick_bits, s.w.cx);
    s.w.cy = vx_sel(m, ty << g.brick_bits, s.w.cy);
    s.w.cz = vx_sel(m, tz << g.brick_bits, s.w.cz);
    vx_i32 size = vx_i32_splat(edge);
    s.w.nx = vx_sel(m, vx_dda_exit_t_sized(s.w.cx, size, s.w.sx, s.w.ox, s.w.ix), s.w.nx);
    s.w.ny = vx_sel(m, vx_dda_exit_t_sized(s.w.cy, size, s.w.sy, s.w.oy, s.w.iy), s.w.ny);
    s.w.nz = vx_sel(m, vx_dda_exit_t_sized(s.w.cz, size, s.w.sz, s.w.oz, s.w.iz), s.w.nz);
    s.cell = vx_sel(m, 0u, s.cell);
    s.w.status = vx_sel(m && outside, VX_STATUS_MISS, s.w.status);
    return s;
}

/* One step of every live lane: at top level, look the top cell up (through the page
 * table) and descend into it if it is not empty; then, at voxel level (just descended
 * too, so a ray that hits the voxel it enters a cell by needs no extra step), test the
 * voxel; then hit or move on, ascending when a voxel walk leaves its top cell. */
VX_FN vx_bm_state vx_brickmap_step(VX_BLOB blob, vx_brickmap g, vx_bm_state s) {
    int edge = 1 << g.brick_bits;
    vx_mask live = s.w.status == VX_STATUS_ACTIVE;
    vx_mask at_top = live && s.cell == 0u;
    vx_i32 tx = s.w.cx >> g.brick_bits, ty = s.w.cy >> g.brick_bits, tz = s.w.cz >> g.brick_bits;

    vx_u32 value = vx_bm_cell(blob, g, tx, ty, tz, at_top);
    vx_mask enter = at_top && value != VX_BM_CELL_EMPTY;
    /* Guards on vx_any keep SIMD lanes from paying for work no lane needs. */
    if (vx_any(enter)) s = vx_bm_descend(s, g, value, enter);

    vx_mask at_voxel = live && s.cell != 0u;
    vx_u32 brick = vx_bm_brick(g, s.cell);
    vx_mask in_brick = at_voxel && brick != 0u;
    vx_u32 bit = vx_bm_voxel_bit(g, s.w.cx, s.w.cy, s.w.cz);
    vx_u32 word = vx_gather_masked(blob, in_brick, brick + (bit >> 5u));
    vx_mask solid = at_voxel && (!in_brick || ((word >> (bit & 31u)) & 1u) != 0u);
    s.w.status = vx_sel(solid, VX_STATUS_HIT, s.w.status);

    vx_mask go = live && !solid;
    s.w = vx_dda_move_sized(s.w, go, vx_sel(at_voxel, 1, edge));
    vx_mask moving_on = go && s.w.status == VX_STATUS_ACTIVE;
    vx_mask leaves_map = moving_on && !at_voxel &&
                         (s.w.cx < 0 || s.w.cy < 0 || s.w.cz < 0 || (s.w.cx >> g.brick_bits) >= g.cells_x ||
                          (s.w.cy >> g.brick_bits) >= g.cells_y || (s.w.cz >> g.brick_bits) >= g.cells_z);
    s.w.status = vx_sel(leaves_map, VX_STATUS_MISS, s.w.status);
    vx_mask leaves_cell = moving_on && at_voxel &&
                          ((s.w.cx >> g.brick_bits) != tx || (s.w.cy >> g.brick_bits) != ty || (s.w.cz >> g.brick_bits) != tz);
    if (vx_any(leaves_cell)) s = vx_bm_ascend(s, g, leaves_cell);
    return s;
}

VX_FN vx_u32 vx_brickmap_status(vx_bm_state s) { return s.w.status; }

/* The hit record; any-hit (a constant `mode`) reads no payload. */
VX_FN vx_hit vx_brickmap_finish(VX_BLOB blob, vx_brickmap g, vx_bm_state s, vx_ray r, uint mode) {
    VX_UNUSED(r);
    vx_mask is_hit = s.w.status == VX_STATUS_HIT;
    vx_u32 payload = vx_u32_splat(0u);
    if (mode == VX_MODE_CLOSEST) {
        vx_u32 brick = vx_bm_brick(g, vx_sel(is_hit, s.cell, 0u));
        vx_mask in_brick = is_hit && brick != 0u;
        vx_u32 bit = vx_bm_voxel_bit(g, s.w.cx, s.w.cy, s.w.cz);
        vx_u32 word = vx_gather_masked(blob, in_brick, brick + g.occupancy_words + (bit >> g.values_per_word_bits));
        vx_u32 shift = (bit & ((1u << g.values_per_word_bits) - 1u)) * g.payload_bits;
        payload = vx_sel(in_brick, (word >> shift) & g.payload_mask, VX_BM_CELL_VALUE(s.cell));
    }
    return vx_hit_from_walk(s.w, g.ox, g.oy, g.oz, payload);
}

/* Closest hit, or any hit (the first solid voxel serves both; any-hit skips the payload). */
VX_FN vx_hit vx_brickmap_trace(VX_BLOB blob, vx_ray r, uint mode) {
    vx_brickmap g = vx_brickmap_load(blob);
    vx_bm_state s = vx_brickmap_begin(g, r);
    while (vx_any(s.w.status == VX_STATUS_ACTIVE)) s = vx_brickmap_step(blob, g, s);
    return vx_brickmap_finish(blob, g, s, r, mode);
}
