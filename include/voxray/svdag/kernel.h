/* Traversal of the sparse voxel DAG (svdag/layout.h): a front-to-back walk with a
 * per-level stack (kernels/stack.h) that holds, for every depth down to `level`, the
 * node on the path to the voxel the walk is in. Each step does one thing per lane:
 *   - in an interior node, descend into the octant holding the walk's voxel, if present;
 *   - in a leaf, a solid voxel is the hit;
 *   - else the walk leaves the empty cube it is in (an absent octant, an empty 2x2x2 quad
 *     of a leaf, or one voxel) in one move (vx_dda_leave_box, the spine's exact crossing
 *     rule), and pops to the deepest node that still holds its new voxel (the common
 *     high bits of the old and new coordinates say which).
 * So lanes at different depths do the same work per step (no lane waits for another's
 * descent), the walk is always at voxel level in voxel units (hits, t and faces are the
 * reference DDA's, bit for bit; only the number of steps differs), and every move leaves
 * a cube holding the current voxel, so the walk ends without any step cap.
 * Attributes are a separate step at the end (closest hit only): the depth-first index of
 * the hit voxel from the counts along its path, then its payload byte or colour block.
 * Needs prelude.h, ray.h, dda.h, stack.h, bits.h. Included once per lane set; no include
 * guard on purpose. */
#include "voxray/svdag/layout.h"

VX_STRUCT(vx_svdag)
    int ox, oy, oz;       /* world position of walk voxel (0,0,0) */
    int ex, ey, ez;       /* world size in voxels */
    int shx, shy, shz;    /* DAG coordinate of walk voxel (0,0,0) */
    int depth;            /* D */
    uint root;
    uint attribute_kind, attributes, colours, search_top, block_count;
VX_END_STRUCT(vx_svdag)

VX_STRUCT(vx_sv_state)
    vx_dda w;             /* the walk over voxels */
    vx_f32 dx, dy, dz;    /* direction, for the exact exit of an empty cube */
    vx_i32 level;         /* depth of `node` */
    vx_u32 node;          /* the node at `level` on the path to the walk's voxel */
    vx_stack path;        /* slot[d]: the node at depth d on that path, d <= level */
VX_END_STRUCT(vx_sv_state)

VX_FN vx_svdag vx_svdag_load(VX_BLOB blob) {
    vx_svdag g;
    g.ox = vx_u2i(vx_load(blob, VX_SV_HEADER_ORIGIN + 0));
    g.oy = vx_u2i(vx_load(blob, VX_SV_HEADER_ORIGIN + 1));
    g.oz = vx_u2i(vx_load(blob, VX_SV_HEADER_ORIGIN + 2));
    g.ex = vx_u2i(vx_load(blob, VX_SV_HEADER_EXTENT + 0));
    g.ey = vx_u2i(vx_load(blob, VX_SV_HEADER_EXTENT + 1));
    g.ez = vx_u2i(vx_load(blob, VX_SV_HEADER_EXTENT + 2));
    g.shx = vx_u2i(vx_load(blob, VX_SV_HEADER_SHIFT + 0));
    g.shy = vx_u2i(vx_load(blob, VX_SV_HEADER_SHIFT + 1));
    g.shz = vx_u2i(vx_load(blob, VX_SV_HEADER_SHIFT + 2));
    g.depth = vx_u2i(vx_load(blob, VX_SV_HEADER_DEPTH));
    g.root = vx_load(blob, VX_SV_HEADER_ROOT);
    g.attribute_kind = vx_load(blob, VX_SV_HEADER_ATTRIBUTE_KIND);
    g.attributes = vx_load(blob, VX_SV_HEADER_ATTRIBUTES);
    g.colours = vx_load(blob, VX_SV_HEADER_COLOURS);
    g.search_top = vx_load(blob, VX_SV_HEADER_SEARCH_TOP);
    g.block_count = vx_load(blob, VX_SV_HEADER_ATTRIBUTE_COUNT);
    return g;
}

VX_FN vx_sv_state vx_svdag_begin(vx_svdag g, vx_ray r) {
    vx_sv_state s;
    s.w = vx_dda_begin_scaled(r, vx_i2f(g.ox), vx_i2f(g.oy), vx_i2f(g.oz), g.ex, g.ey, g.ez, 1.0f);
    s.dx = r.dx; s.dy = r.dy; s.dz = r.dz;
    s.level = vx_i32_splat(0);
    s.node = vx_u32_splat(g.root);
    for (int d = 0; d < VX_STACK_DEPTH; ++d) s.path.slot[d] = vx_u32_splat(g.root);
    return s;
}

/* Descents per step: a fresh ray starts at the root, D - 2 levels above its leaf, so each
 * step takes up to this many levels at once (lanes that need fewer are masked; a step that
 * only descended is one of these loops, not a whole step's overhead per level). */
#define VX_SV_DESCENTS 3

/* One step of every live lane (see the top comment). */
VX_FN vx_sv_state vx_svdag_step(VX_BLOB blob, vx_svdag g, vx_sv_state s) {
    vx_u32 one = vx_u32_splat(1u);
    vx_mask live = s.w.status == VX_STATUS_ACTIVE;
    vx_i32 gx = s.w.cx + g.shx, gy = s.w.cy + g.shy, gz = s.w.cz + g.shz;
    vx_u32 ux = vx_i2u(gx), uy = vx_i2u(gy), uz = vx_i2u(gz);
    int leaf_depth = g.depth - VX_SV_LEAF_EDGE_BITS;

    /* Interior nodes: the octant's child, when present, is the next node down; an absent
     * one blocks the lane, which then leaves the octant's empty cube below. */
    vx_mask blocked = live && !live; /* no lane */
    vx_i32 child_size = vx_i32_splat(1);
    for (int k = 0; k < VX_SV_DESCENTS; ++k) {
        vx_mask inner = live && !blocked && s.level < leaf_depth;
        if (!vx_any(inner)) break;
        vx_u32 child_bit = vx_i2u(g.depth - 1 - s.level);
        vx_u32 octant = VX_SV_OCTANT(ux, uy, uz, child_bit);
        vx_u32 mask = vx_gather_masked(blob, inner, s.node) & VX_SV_NODE_MASK_BITS;
        vx_mask present = inner && ((mask >> octant) & 1u) != 0u;
        vx_u32 child = vx_gather_masked(blob, present,
                                        s.node + VX_SV_NODE_CHILDREN + vx_popcount(VX_SV_BELOW(mask, octant, one)));
        vx_stack_store(VX_ADDR(s.path), s.level + 1, child, present);
        s.node = vx_sel(present, child, s.node);
        s.level = vx_sel(present, s.level + 1, s.level);
        blocked = blocked || (inner && !present);
        child_size = vx_sel(inner && !present, vx_u2i(one << child_bit), child_size);
    }
    vx_mask leaf = live && s.level == leaf_depth;

    /* Leaf: the voxel's bit. */
    vx_u32 i = VX_SV_LEAF_BIT(ux, uy, uz);
    vx_u32 word = vx_gather_masked(blob, leaf, s.node + VX_SV_LEAF_WORD(i));
    vx_mask solid = leaf && ((word >> VX_SV_LEAF_SHIFT(i)) & 1u) != 0u;
    s.w.status = vx_sel(solid, VX_STATUS_HIT, s.w.status);
    vx_mask empty_quad = leaf && (word & VX_SV_QUAD_BITS(ux, uy, one)) == 0u;

    /* Empty: leave the cube (an absent octant, an empty quad, or the voxel). Lanes still
     * descending neither hit nor move. */
    vx_mask go = blocked || (leaf && !solid);
    vx_i32 size = vx_sel(blocked, child_size, vx_sel(empty_quad, vx_i32_splat(2), vx_i32_splat(1)));
    vx_i32 lox = (gx & (0 - size)) - g.shx, loy = (gy & (0 - size)) - g.shy, loz = (gz & (0 - size)) - g.shz;
    s.w = vx_dda_leave_box(s.w, s.dx, s.dy, s.dz, lox, loy, loz, lox + size, loy + size, loz + size, go);
    vx_mask outside = s.w.cx < 0 || s.w.cy < 0 || s.w.cz < 0 || s.w.cx >= g.ex || s.w.cy >= g.ey || s.w.cz >= g.ez;
    s.w.status = vx_sel(go && outside, VX_STATUS_MISS, s.w.status);

    /* Pop to the deepest node holding the new voxel: a node at depth d (edge 2^(D-d))
     * holds it while the coordinates agree above bit D - d. */
    vx_u32 moved = (vx_i2u(s.w.cx + g.shx) ^ ux) | (vx_i2u(s.w.cy + g.shy) ^ uy) | (vx_i2u(s.w.cz + g.shz) ^ uz);
    vx_i32 keep = g.depth - vx_bit_length(moved);
    vx_i32 level = vx_sel(keep < s.level, keep, s.level);
    level = vx_sel(level < 0, 0, level); /* lanes that left the world: any valid slot */
    vx_mask popped = go && level != s.level;
    s.level = vx_sel(go, level, s.level);
    s.node = vx_sel(popped, vx_stack_load(VX_ADDR(s.path), s.level), s.node);
    return s;
}

VX_FN vx_u32 vx_svdag_status(vx_sv_state s) { return s.w.status; }

/* Depth-first index of the solid voxel at DAG coordinates u (lanes m): the voxels of the
 * siblings before its octant on every level, plus the bits below its own in the leaf. */
VX_FN vx_u32 vx_sv_dfs_index(VX_BLOB blob, vx_svdag g, vx_u32 ux, vx_u32 uy, vx_u32 uz, vx_mask m) {
    vx_u32 one = vx_u32_splat(1u);
    vx_u32 node = vx_u32_splat(g.root);
    vx_u32 index = vx_u32_splat(0u);
    for (int d = 0; d < g.depth - VX_SV_LEAF_EDGE_BITS; ++d) {
        vx_u32 octant = VX_SV_OCTANT(ux, uy, uz, vx_u32_splat(vx_i2u(g.depth - 1 - d)));
        vx_u32 mask = vx_gather_masked(blob, m, node) & VX_SV_NODE_MASK_BITS;
        vx_u32 slot = vx_popcount(VX_SV_BELOW(mask, octant, one));
        for (uint k = 0u; k < 7u; ++k) {
            vx_mask before = m && k < slot;
            if (!vx_any(before)) break;
            vx_u32 sibling = vx_gather_masked(blob, before, node + VX_SV_NODE_CHILDREN + k);
            vx_u32 count;
            if (d == g.depth - VX_SV_LEAF_EDGE_BITS - 1) /* the children are leaves */
                count = vx_popcount(vx_gather_masked(blob, before, sibling)) +
                        vx_popcount(vx_gather_masked(blob, before, sibling + 1u));
            else
                count = vx_gather_masked(blob, before, sibling + 1u);
            index = index + vx_sel(before, count, 0u);
        }
        node = vx_gather_masked(blob, m, node + VX_SV_NODE_CHILDREN + slot);
    }
    vx_u32 i = VX_SV_LEAF_BIT(ux, uy, uz);
    vx_u32 low = vx_gather_masked(blob, m, node);
    vx_u32 high = vx_gather_masked(blob, m, node + 1u);
    vx_u32 below_bits = (one << VX_SV_LEAF_SHIFT(i)) - 1u;
    return index + vx_sel(i < 32u, vx_popcount(low & below_bits), vx_popcount(low) + vx_popcount(high & below_bits));
}

/* The attribute of depth-first index `index`: its payload byte (exact), or the RGBA8
 * colour of the block holding it (the last block starting at or before it). */
VX_FN vx_u32 vx_sv_attribute(VX_BLOB blob, vx_svdag g, vx_u32 index, vx_mask m) {
    if (g.attribute_kind == VX_SV_ATTRIBUTES_EXACT) {
        vx_u32 word = vx_gather_masked(blob, m, g.attributes + VX_SV_ATTRIBUTE_WORD(index));
        return (word >> VX_SV_ATTRIBUTE_SHIFT(index)) & 255u;
    }
    vx_u32 block = vx_u32_splat(0u);
    for (uint stride = g.search_top; stride > 0u; stride = stride >> 1u) {
        vx_mask inside = m && block + stride < g.block_count;
        vx_u32 start = vx_gather_masked(blob, inside, g.attributes + block + stride);
        block = vx_sel(inside && start <= index, block + stride, block);
    }
    return vx_gather_masked(blob, m, g.colours + block);
}

/* The hit record; any-hit (a constant `mode`) skips the attribute lookup. */
VX_FN vx_hit vx_svdag_finish(VX_BLOB blob, vx_svdag g, vx_sv_state s, uint mode) {
    vx_hit h;
    vx_mask is_hit = s.w.status == VX_STATUS_HIT;
    h.material = vx_u32_splat(0u);
    if (mode == VX_MODE_CLOSEST) {
        vx_u32 ux = vx_i2u(s.w.cx + g.shx), uy = vx_i2u(s.w.cy + g.shy), uz = vx_i2u(s.w.cz + g.shz);
        vx_u32 index = vx_sv_dfs_index(blob, g, ux, uy, uz, is_hit);
        h.material = vx_sel(is_hit, vx_sv_attribute(blob, g, index, is_hit), 0u);
    }
    h.t = vx_sel(is_hit, s.w.t, VX_INF);
    h.x = vx_sel(is_hit, s.w.cx + g.ox, 0);
    h.y = vx_sel(is_hit, s.w.cy + g.oy, 0);
    h.z = vx_sel(is_hit, s.w.cz + g.oz, 0);
    h.face = vx_sel(is_hit, s.w.face, VX_FACE_NONE);
    h.steps = s.w.steps;
    h.status = s.w.status;
    return h;
}

/* Closest hit, or any hit (the first solid voxel serves both; any-hit skips attributes). */
VX_FN vx_hit vx_svdag_trace(VX_BLOB blob, vx_ray r, uint mode) {
    vx_svdag g = vx_svdag_load(blob);
    vx_sv_state s = vx_svdag_begin(g, r);
    while (vx_any(s.w.status == VX_STATUS_ACTIVE)) s = vx_svdag_step(blob, g, s);
    return vx_svdag_finish(blob, g, s, mode);
}
