/* Traversal of the dense reference grid (dense_grid/layout.h): the exact DDA
 * visits every cell and tests its occupancy bit. Needs prelude.h, ray.h and dda.h first.
 * Included once per lane set; no include guard on purpose (see kernels/kernel_tag.inc). */
#include "voxray/dense_grid/layout.h"

/* Header fields every step needs, read once per ray (uniform across lanes). */
VX_STRUCT(vx_dense_grid)
    int ox, oy, oz;      /* world position of voxel (0,0,0) */
    int ex, ey, ez;      /* extent in voxels */
    uint chunks_x, chunks_xy;
    uint table, data;    /* word offsets */
VX_END_STRUCT(vx_dense_grid)

VX_FN vx_dense_grid vx_dense_grid_load(VX_BLOB blob) {
    vx_dense_grid g;
    g.ox = vx_u2i(vx_load(blob, VX_DG_HEADER_ORIGIN + 0));
    g.oy = vx_u2i(vx_load(blob, VX_DG_HEADER_ORIGIN + 1));
    g.oz = vx_u2i(vx_load(blob, VX_DG_HEADER_ORIGIN + 2));
    g.ex = vx_u2i(vx_load(blob, VX_DG_HEADER_EXTENT + 0));
    g.ey = vx_u2i(vx_load(blob, VX_DG_HEADER_EXTENT + 1));
    g.ez = vx_u2i(vx_load(blob, VX_DG_HEADER_EXTENT + 2));
    g.chunks_x = vx_load(blob, VX_DG_HEADER_CHUNKS + 0);
    g.chunks_xy = g.chunks_x * vx_load(blob, VX_DG_HEADER_CHUNKS + 1);
    g.table = vx_load(blob, VX_DG_HEADER_TABLE);
    g.data = vx_load(blob, VX_DG_HEADER_DATA);
    return g;
}

/* Word offset of the chunk record holding cell (cx, cy, cz), or VX_DG_EMPTY_CHUNK.
 * Lanes outside `live` read word 0 instead (always in bounds). */
VX_FN vx_u32 vx_dense_chunk(VX_BLOB blob, vx_dense_grid g, vx_i32 cx, vx_i32 cy, vx_i32 cz, vx_mask live) {
    vx_u32 slot = VX_DG_CHUNK_SLOT(vx_i2u(cx), vx_i2u(cy), vx_i2u(cz), g.chunks_x, g.chunks_xy);
    vx_u32 entry = vx_gather(blob, vx_sel(live, g.table + slot, 0u));
    vx_mask present = live && entry != VX_DG_EMPTY_CHUNK;
    return vx_sel(present, g.data + entry * VX_DG_CHUNK_WORDS, VX_DG_EMPTY_CHUNK);
}

/* One step: a hit if the current cell is solid, else move to the next cell. */
VX_FN vx_dda vx_dense_grid_step(VX_BLOB blob, vx_dense_grid g, vx_dda d) {
    vx_mask live = d.status == VX_STATUS_ACTIVE;
    vx_u32 chunk = vx_dense_chunk(blob, g, d.cx, d.cy, d.cz, live);
    vx_mask present = chunk != VX_DG_EMPTY_CHUNK;
    vx_u32 cell_bit = vx_i2u(VX_DG_LOCAL(d.cx, d.cy, d.cz));
    /* Most steps cross empty chunks: no occupancy load when no lane needs it. */
    vx_u32 bits = vx_gather_masked(blob, present, chunk + VX_DG_OCCUPANCY_WORD(cell_bit));
    vx_mask solid = present && ((bits >> (cell_bit & 31u)) & 1u) != 0u;
    d.status = vx_sel(solid, VX_STATUS_HIT, d.status);
    return vx_dda_advance(d, live && !solid, g.ex, g.ey, g.ez);
}

/* The hit record; any-hit (a constant `mode`) reads no material. */
VX_FN vx_hit vx_dense_grid_finish(VX_BLOB blob, vx_dense_grid g, vx_dda d, vx_ray r, uint mode) {
    VX_UNUSED(r);
    vx_mask is_hit = d.status == VX_STATUS_HIT;
    vx_u32 word = vx_u32_splat(0u);
    vx_u32 cell_bit = vx_i2u(VX_DG_LOCAL(d.cx, d.cy, d.cz));
    if (mode == VX_MODE_CLOSEST) {
        vx_u32 chunk = vx_dense_chunk(blob, g, d.cx, d.cy, d.cz, is_hit);
        vx_mask present = chunk != VX_DG_EMPTY_CHUNK;
        word = vx_gather_masked(blob, present, chunk + VX_DG_MATERIAL_WORD(cell_bit));
    }
    return vx_hit_from_walk(d, g.ox, g.oy, g.oz, (word >> VX_DG_MATERIAL_SHIFT(cell_bit)) & 255u);
}

VX_FN vx_u32 vx_dense_grid_status(vx_dda d) { return d.status; }

VX_FN vx_dda vx_dense_grid_begin(vx_dense_grid g, vx_ray r) {
    return vx_dda_begin_scaled(r, vx_i2f(g.ox), vx_i2f(g.oy), vx_i2f(g.oz), g.ex, g.ey, g.ez, 1.0f);
}

/* Closest hit, or any hit (the first solid cell serves both; any-hit skips the material).
 * The state machine (load, begin, step until not active, finish) is also driven directly
 * by the CPU's SIMD stream, which refills finished lanes with new rays. */
VX_FN vx_hit vx_dense_grid_trace(VX_BLOB blob, vx_ray r, uint mode) {
    vx_dense_grid g = vx_dense_grid_load(blob);
    vx_dda d = vx_dense_grid_begin(g, r);
    while (vx_any(d.status == VX_STATUS_ACTIVE)) d = vx_dense_grid_step(blob, g, d);
    return vx_dense_grid_finish(blob, g, d, r, mode);
}
