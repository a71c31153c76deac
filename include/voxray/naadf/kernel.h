/* Traversal of NAADF (naadf/layout.h): one loop with no stack. Each step looks the voxel
 * the walk is in up from the top (page, chunk, block, voxel) and stops at the first layer
 * that is not mixed. A uniform cell or a solid voxel is the hit; an empty cell's AADF
 * describes an empty cuboid around it, which the walk leaves in one move
 * (vx_dda_leave_box, the spine's exact crossing rule). The walk is always at voxel level,
 * in voxel units, so the hit voxel, t and face are those the reference DDA finds, bit for
 * bit; only the number of steps differs. Every move leaves a cuboid that holds the current
 * voxel, so the walk ends without any step cap.
 * Needs prelude.h, ray.h, dda.h. Included once per lane set; no include guard on purpose. */
#include "voxray/naadf/layout.h"

VX_STRUCT(vx_naadf)
    int ox, oy, oz;       /* world position of voxel (0,0,0) */
    int ex, ey, ez;       /* world size in voxels */
    int shx, shy, shz;    /* grid coordinate of voxel (0,0,0) */
    uint pages_x, pages_xy;
    uint page_table, chunks, blocks, voxels;
VX_END_STRUCT(vx_naadf)

VX_STRUCT(vx_na_state)
    vx_dda w;             /* the walk over voxels */
    vx_f32 dx, dy, dz;    /* direction, for the exact exit of a cuboid */
    vx_u32 type;          /* the hit cell's type, kept so finishing needs no second lookup */
VX_END_STRUCT(vx_na_state)

/* The cell a voxel lies in at the highest layer that is not mixed. */
VX_STRUCT(vx_na_cell)
    vx_u32 value;         /* its cell word, or the voxel's 16 bits */
    vx_i32 level;         /* log2 of its edge: 8 page, 4 chunk, 2 block, 0 voxel */
    vx_mask solid;        /* uniform cell or solid voxel */
VX_END_STRUCT(vx_na_cell)

VX_FN vx_naadf vx_naadf_load(VX_BLOB blob) {
    vx_naadf g;
    g.ox = vx_u2i(vx_load(blob, VX_NA_HEADER_ORIGIN + 0));
    g.oy = vx_u2i(vx_load(blob, VX_NA_HEADER_ORIGIN + 1));
    g.oz = vx_u2i(vx_load(blob, VX_NA_HEADER_ORIGIN + 2));
    g.ex = vx_u2i(vx_load(blob, VX_NA_HEADER_EXTENT + 0));
    g.ey = vx_u2i(vx_load(blob, VX_NA_HEADER_EXTENT + 1));
    g.ez = vx_u2i(vx_load(blob, VX_NA_HEADER_EXTENT + 2));
    g.shx = vx_u2i(vx_load(blob, VX_NA_HEADER_SHIFT + 0));
    g.shy = vx_u2i(vx_load(blob, VX_NA_HEADER_SHIFT + 1));
    g.shz = vx_u2i(vx_load(blob, VX_NA_HEADER_SHIFT + 2));
    g.pages_x = vx_load(blob, VX_NA_HEADER_PAGES_DIM + 0);
    g.pages_xy = g.pages_x * vx_load(blob, VX_NA_HEADER_PAGES_DIM + 1);
    g.page_table = vx_load(blob, VX_NA_HEADER_PAGE_TABLE);
    g.chunks = vx_load(blob, VX_NA_HEADER_CHUNKS);
    g.blocks = vx_load(blob, VX_NA_HEADER_BLOCKS);
    g.voxels = vx_load(blob, VX_NA_HEADER_VOXELS);
    return g;
}

/* Looks grid voxel (gx, gy, gz) up in lanes `live` (inside the world): one load per layer
 * until a layer is not mixed; lanes that stop early load nothing further. */
VX_FN vx_na_cell vx_na_lookup(VX_BLOB blob, vx_naadf g, vx_i32 gx, vx_i32 gy, vx_i32 gz, vx_mask live) {
    vx_na_cell c;
    vx_u32 ux = vx_i2u(gx), uy = vx_i2u(gy), uz = vx_i2u(gz);
    vx_u32 page = vx_gather_masked(blob, live, g.page_table + VX_NA_PAGE_SLOT(ux, uy, uz, g.pages_x, g.pages_xy));
    vx_mask down = live && VX_NA_STATE(page) == VX_NA_MIXED;
    vx_u32 chunk = vx_gather_masked(blob, down,
                                    g.chunks + VX_NA_PAYLOAD(page) * VX_NA_CHUNK_ARRAY_WORDS + VX_NA_CHUNK_INDEX(ux, uy, uz));
    c.value = vx_sel(down, chunk, page);
    c.level = vx_sel(down, vx_i32_splat(VX_NA_CHUNK_BITS), vx_i32_splat(VX_NA_PAGE_BITS));
    down = down && VX_NA_STATE(chunk) == VX_NA_MIXED;
    vx_u32 block = vx_gather_masked(blob, down,
                                    g.blocks + VX_NA_PAYLOAD(chunk) * VX_NA_BLOCK_ARRAY_WORDS + VX_NA_BLOCK_INDEX(ux, uy, uz));
    c.value = vx_sel(down, block, c.value);
    c.level = vx_sel(down, vx_i32_splat(VX_NA_BLOCK_BITS), c.level);
    down = down && VX_NA_STATE(block) == VX_NA_MIXED;
    vx_u32 i = VX_NA_VOXEL_INDEX(ux, uy, uz);
    vx_u32 word = vx_gather_masked(blob, down, g.voxels + VX_NA_PAYLOAD(block) * VX_NA_GROUP_WORDS + VX_NA_VOXEL_WORD(i));
    vx_u32 voxel = (word >> VX_NA_VOXEL_SHIFT(i)) & 0xFFFFu;
    c.value = vx_sel(down, voxel, c.value);
    c.level = vx_sel(down, vx_i32_splat(0), c.level);
    c.solid = live && ((down && (voxel & VX_NA_VOXEL_SOLID) != 0u) ||
                       (!down && VX_NA_STATE(c.value) == VX_NA_UNIFORM));
    return c;
}

VX_FN vx_na_state vx_naadf_begin(vx_naadf g, vx_ray r) {
    vx_na_state s;
    s.w = vx_dda_begin_scaled(r, vx_i2f(g.ox), vx_i2f(g.oy), vx_i2f(g.oz), g.ex, g.ey, g.ez, 1.0f);
    s.dx = r.dx; s.dy = r.dy; s.dz = r.dz;
    s.type = vx_u32_splat(0u);
    return s;
}

/* One step of every live lane: hit the cell the walk is in, or leave the empty cuboid its
 * AADF gives (in walk coordinates: the cell's min corner, widened by the fields times the
 * cell's edge). Leaving the world is a miss. */
VX_FN vx_na_state vx_naadf_step(VX_BLOB blob, vx_naadf g, vx_na_state s) {
    vx_mask live = s.w.status == VX_STATUS_ACTIVE;
    vx_i32 gx = s.w.cx + g.shx, gy = s.w.cy + g.shy, gz = s.w.cz + g.shz;
    vx_na_cell c = vx_na_lookup(blob, g, gx, gy, gz, live);
    s.w.status = vx_sel(c.solid, VX_STATUS_HIT, s.w.status);
    s.type = vx_sel(c.solid, c.value & VX_NA_TYPE_MASK, s.type);

    vx_mask go = live && !c.solid;
    vx_u32 k = vx_sel(c.level >= VX_NA_CHUNK_BITS, vx_u32_splat(VX_NA_CHUNK_AADF_BITS), vx_u32_splat(VX_NA_BLOCK_AADF_BITS));
    vx_u32 one = vx_u32_splat(1u);  /* VX_NA_AADF_FIELD shifts 1u by the per-lane field width */
    vx_i32 size = vx_i32_splat(1) << c.level;
    vx_i32 mx = (gx & (0 - size)) - g.shx, my = (gy & (0 - size)) - g.shy, mz = (gz & (0 - size)) - g.shz;
    vx_i32 lox = mx - vx_u2i(VX_NA_AADF_FIELD(c.value, one, k)) * size;
    vx_i32 hix = mx + size + vx_u2i(VX_NA_AADF_FIELD(c.value, 0u, k)) * size;
    vx_i32 loy = my - vx_u2i(VX_NA_AADF_FIELD(c.value, 3u, k)) * size;
    vx_i32 hiy = my + size + vx_u2i(VX_NA_AADF_FIELD(c.value, 2u, k)) * size;
    vx_i32 loz = mz - vx_u2i(VX_NA_AADF_FIELD(c.value, 5u, k)) * size;
    vx_i32 hiz = mz + size + vx_u2i(VX_NA_AADF_FIELD(c.value, 4u, k)) * size;
    s.w = vx_dda_leave_box(s.w, s.dx, s.dy, s.dz, lox, loy, loz, hix, hiy, hiz, go);

    vx_mask outside = s.w.cx < 0 || s.w.cy < 0 || s.w.cz < 0 || s.w.cx >= g.ex || s.w.cy >= g.ey || s.w.cz >= g.ez;
    s.w.status = vx_sel(go && outside, VX_STATUS_MISS, s.w.status);
    return s;
}

VX_FN vx_u32 vx_naadf_status(vx_na_state s) { return s.w.status; }

/* The hit record; the type was kept at the hit step (any-hit reports none, like the
 * other structures). */
VX_FN vx_hit vx_naadf_finish(VX_BLOB blob, vx_naadf g, vx_na_state s, vx_ray r, uint mode) {
    VX_UNUSED(r);
    VX_UNUSED(blob);
    return vx_hit_from_walk(s.w, g.ox, g.oy, g.oz, mode == VX_MODE_CLOSEST ? s.type : vx_u32_splat(0u));
}

/* Closest hit, or any hit (the first solid voxel serves both; any-hit skips the type). */
VX_FN vx_hit vx_naadf_trace(VX_BLOB blob, vx_ray r, uint mode) {
    vx_naadf g = vx_naadf_load(blob);
    vx_na_state s = vx_naadf_begin(g, r);
    while (vx_any(s.w.status == VX_STATUS_ACTIVE)) s = vx_naadf_step(blob, g, s);
    return vx_naadf_finish(blob, g, s, r, mode);
}
