/* The walk through sparse voxel DAGs (svdag/layout.h), shared by the DAG's own kernel
 * (svdag/kernel.h) and the chunked world's (world/kernel.h), whose lanes each walk their
 * own chunk's DAG at their own level of detail. Part of the common dialect: compiled once
 * per GPU program and CPU lane set, so two structures' kernels in one program (or one
 * user shader) share it.
 *
 * A front-to-back walk with a per-level stack (kernels/stack.h) that holds, for every depth
 * down to `level`, the node on the path to the voxel the walk is in. Each step does one
 * thing per lane:
 *   - in an interior node, descend into the octant holding the walk's voxel, if present;
 *   - in a leaf, a solid voxel is the hit;
 *   - else the walk leaves the empty cube it is in (an absent octant, an empty 2x2x2 quad
 *     of a leaf, or one voxel) in one move (vx_dda_leave_box, the spine's exact crossing
 *     rule), and pops to the deepest node that still holds its new voxel (the common
 *     high bits of the old and new coordinates say which); a walk that leaves the DAG's
 *     cube pops to level -1.
 * So lanes at different depths do the same work per step, the walk is always at voxel
 * level in walk voxels (hits, t and faces are the reference DDA's, bit for bit; only the
 * number of steps differs), and every move leaves a cube holding the current voxel, so
 * the walk ends without any step cap.
 *
 * Which DAG a lane is in is per lane (its state), what all DAGs share is uniform (the frame):
 *   state.base  word offset of the DAG's header; pointers in a DAG are relative to it
 *   state.lod   walk voxels per DAG voxel, as a shift: a DAG voxel is 2^lod walk voxels
 *   frame       the DAGs' depth D, the shift from walk to DAG coordinates (DAG coordinate
 *               = (walk + shift) >> lod), and the walk's extent (leaving it is a miss)
 * A DAG voxel of LOD n is a 2^n cube of walk voxels: the walk still moves voxel by voxel
 * through it, and enters it exactly where the ray crosses its boundary, so a coarse hit
 * has the exact t and face of the coarse cube. Octant bits are taken below bit D of the
 * DAG coordinate, so a DAG placed at any multiple of its edge needs no subtraction.
 * Needs prelude.h, ray.h, dda.h, stack.h, bits.h. */
#include "voxray/svdag/layout.h"

VX_STRUCT(vx_sv_frame)
    int depth;            /* D: every DAG is 2^D voxels a side */
    int shx, shy, shz;    /* DAG coordinate (at lod 0) of walk voxel (0,0,0) */
    int ex, ey, ez;       /* the walk's extent in voxels */
VX_END_STRUCT(vx_sv_frame)

VX_STRUCT(vx_sv_state)
    vx_dda w;             /* the walk over voxels */
    vx_f32 dx, dy, dz;    /* direction, for the exact exit of an empty cube */
    vx_i32 level;         /* depth of `node`; -1: in no DAG */
    vx_u32 base;          /* the DAG's header (pointers are relative to it) */
    vx_u32 lod;           /* walk voxels per DAG voxel, as a shift */
    vx_u32 node;          /* the node at `level` on the path to the walk's voxel */
    vx_stack path;        /* slot[d]: the node at depth d on that path, d <= level */
VX_END_STRUCT(vx_sv_state)

/* A walk over the frame's extent whose walk voxel (0,0,0) is at world (ox, oy, oz), in no DAG yet. */
VX_FN vx_sv_state vx_sv_begin(vx_sv_frame f, vx_ray r, int ox, int oy, int oz) {
    vx_sv_state s;
    s.w = vx_dda_begin_scaled(r, vx_i2f(ox), vx_i2f(oy), vx_i2f(oz), f.ex, f.ey, f.ez, 1.0f);
    s.dx = r.dx; s.dy = r.dy; s.dz = r.dz;
    s.level = vx_i32_splat(-1);
    s.base = vx_u32_splat(0u);
    s.lod = vx_u32_splat(0u);
    s.node = vx_u32_splat(0u);
    for (int d = 0; d < VX_STACK_DEPTH; ++d) s.path.slot[d] = vx_u32_splat(0u);
    return s;
}

/* Lanes m enter, at its root, the DAG whose header is at `base`, at level of detail `lod`.
 * The root follows the header (VX_SV_HEADER_ROOT; svdag/validate.hpp checks it). */
VX_FN vx_sv_state vx_sv_enter(vx_sv_state s, vx_u32 base, vx_u32 lod, vx_mask m) {
    vx_u32 root = base + VX_SV_HEADER_WORDS;
    s.base = vx_sel(m, base, s.base);
    s.lod = vx_sel(m, lod, s.lod);
    s.level = vx_sel(m, 0, s.level);
    s.node = vx_sel(m, root, s.node);
    vx_stack_store(VX_ADDR(s.path), vx_i32_splat(0), root, m);
    return s;
}

/* Lanes m, whose walk `old` has ended, start the walk `s` of a new ray (begun and entered at
 * the root of the same DAG) at the deepest node on old's path that holds the new ray's
 * first voxel, rather than at the root: the pop rule of vx_sv_step, applied to the jump
 * from old's voxel to the new one. Rays from one camera, or from neighbouring pixels'
 * surfaces, share most of the descent. The walk meets the same voxels either way. */
VX_FN vx_sv_state vx_sv_resume(vx_sv_frame f, vx_sv_state old, vx_sv_state s, vx_mask m) {
    vx_u32 moved = ((vx_i2u(s.w.cx + f.shx) >> s.lod) ^ (vx_i2u(old.w.cx + f.shx) >> old.lod)) |
                   ((vx_i2u(s.w.cy + f.shy) >> s.lod) ^ (vx_i2u(old.w.cy + f.shy) >> old.lod)) |
                   ((vx_i2u(s.w.cz + f.shz) >> s.lod) ^ (vx_i2u(old.w.cz + f.shz) >> old.lod));
    vx_i32 keep = f.depth - vx_bit_length(moved);
    vx_i32 level = vx_sel(keep < old.level, keep, old.level);
    vx_mask reuse = m && s.w.status == VX_STATUS_ACTIVE && s.level == 0 && old.base == s.base && old.lod == s.lod &&
                    level > 0;
    if (!vx_any(reuse)) return s;
    s.level = vx_sel(reuse, level, s.level);
    s.node = vx_sel(reuse, vx_stack_load(VX_ADDR(old.path), vx_sel(reuse, level, 0)), s.node);
    for (int d = 1; d < VX_STACK_DEPTH; ++d) s.path.slot[d] = vx_sel(reuse, old.path.slot[d], s.path.slot[d]);
    return s;
}

/* Lanes m leave the empty box [lo, hi) (walk voxels) in one move; leaving the frame's
 * extent is a miss. */
VX_FN vx_sv_state vx_sv_leave(vx_sv_frame f, vx_sv_state s, vx_i32 lox, vx_i32 loy, vx_i32 loz, vx_i32 hix,
                              vx_i32 hiy, vx_i32 hiz, vx_mask m) {
    s.w = vx_dda_leave_box(s.w, s.dx, s.dy, s.dz, lox, loy, loz, hix, hiy, hiz, m);
    vx_mask outside = s.w.cx < 0 || s.w.cy < 0 || s.w.cz < 0 || s.w.cx >= f.ex || s.w.cy >= f.ey || s.w.cz >= f.ez;
    s.w.status = vx_sel(m && outside, VX_STATUS_MISS, s.w.status);
    return s;
}

/* Descents per step: a fresh ray starts at the root, D - 2 levels above its leaf, so each
 * step takes up to this many levels at once (lanes that need fewer are masked; a step that
 * only descended is one of these loops, not a whole step's overhead per level). */
#define VX_SV_DESCENTS 3

/* One step (see the top comment) of lanes `live`, which are active and in a DAG (level >= 0). */
VX_FN vx_sv_state vx_sv_step(VX_BLOB blob, vx_sv_frame f, vx_sv_state s, vx_mask live) {
    vx_u32 one = vx_u32_splat(1u);
    vx_u32 ux = vx_i2u(s.w.cx + f.shx) >> s.lod, uy = vx_i2u(s.w.cy + f.shy) >> s.lod,
           uz = vx_i2u(s.w.cz + f.shz) >> s.lod;
    int leaf_depth = f.depth - VX_SV_LEAF_EDGE_BITS;

    /* Interior nodes: the octant's child, when present, is the next node down; an absent
     * one blocks the lane, which then leaves the octant's empty cube below. */
    vx_mask blocked = live && !live; /* no lane */
    vx_u32 child_size = one;
    for (int k = 0; k < VX_SV_DESCENTS; ++k) {
        vx_mask inner = live && !blocked && s.level < leaf_depth;
        if (!vx_any(inner)) break;
        vx_u32 child_bit = vx_i2u(f.depth - 1 - s.level);
        vx_u32 octant = VX_SV_OCTANT(ux, uy, uz, child_bit);
        vx_u32 mask = vx_gather_masked(blob, inner, s.node) & VX_SV_NODE_MASK_BITS;
        vx_mask present = inner && ((mask >> octant) & 1u) != 0u;
        vx_u32 child = s.base + vx_gather_masked(blob, present,
                                                 s.node + VX_SV_NODE_CHILDREN + vx_popcount(VX_SV_BELOW(mask, octant, one)));
        vx_stack_store(VX_ADDR(s.path), s.level + 1, child, present);
        s.node = vx_sel(present, child, s.node);
        s.level = vx_sel(present, s.level + 1, s.level);
        blocked = blocked || (inner && !present);
        child_size = vx_sel(inner && !present, one << child_bit, child_size);
    }
    vx_mask leaf = live && s.level == leaf_depth;

    /* Leaf: the voxel's bit. */
    vx_u32 i = VX_SV_LEAF_BIT(ux, uy, uz);
    vx_u32 word = vx_gather_masked(blob, leaf, s.node + VX_SV_LEAF_WORD(i));
    vx_mask solid = leaf && ((word >> VX_SV_LEAF_SHIFT(i)) & 1u) != 0u;
    s.w.status = vx_sel(solid, VX_STATUS_HIT, s.w.status);
    vx_mask empty_quad = leaf && (word & VX_SV_QUAD_BITS(ux, uy, one)) == 0u;

    /* Empty: leave the cube (an absent octant, an empty quad, or the voxel), in walk voxels.
     * Lanes still descending neither hit nor move. */
    vx_mask go = blocked || (leaf && !solid);
    vx_u32 size = vx_sel(blocked, child_size, vx_sel(empty_quad, vx_u32_splat(2u), one));
    vx_i32 walk_size = vx_u2i(size << s.lod);
    vx_i32 lox = vx_u2i((ux & (0u - size)) << s.lod) - f.shx, loy = vx_u2i((uy & (0u - size)) << s.lod) - f.shy,
           loz = vx_u2i((uz & (0u - size)) << s.lod) - f.shz;
    s = vx_sv_leave(f, s, lox, loy, loz, lox + walk_size, loy + walk_size, loz + walk_size, go);

    /* Pop to the deepest node holding the new voxel: a node at depth d (edge 2^(D-d))
     * holds it while the DAG coordinates agree above bit D - d; none does when they
     * differ at bit D or above (the walk left this DAG's cube: level -1). */
    vx_u32 moved = ((vx_i2u(s.w.cx + f.shx) >> s.lod) ^ ux) | ((vx_i2u(s.w.cy + f.shy) >> s.lod) ^ uy) |
                   ((vx_i2u(s.w.cz + f.shz) >> s.lod) ^ uz);
    vx_i32 keep = f.depth - vx_bit_length(moved);
    vx_i32 level = vx_sel(keep < s.level, keep, s.level);
    level = vx_sel(level < 0, -1, level);
    vx_mask popped = go && level != s.level && level >= 0;
    s.level = vx_sel(go, level, s.level);
    s.node = vx_sel(popped, vx_stack_load(VX_ADDR(s.path), vx_sel(popped, s.level, 0)), s.node);
    return s;
}

/* The solid voxels below the children of `node` (lanes m) before the one of octant o. */
VX_FN vx_u32 vx_sv_below_octant(VX_BLOB blob, vx_u32 node, vx_u32 octant, vx_mask m) {
    vx_u32 mask = vx_gather_masked(blob, m, node) & VX_SV_NODE_MASK_BITS;
    vx_u32 slot = vx_popcount(VX_SV_BELOW(mask, octant, vx_u32_splat(1u)));
    return vx_gather_masked(blob, m && slot > 0u, node + VX_SV_NODE_BELOW(vx_popcount(mask), slot));
}

/* The solid voxels of `leaf` (lanes m) before the one at DAG coordinates u. */
VX_FN vx_u32 vx_sv_below_in_leaf(VX_BLOB blob, vx_u32 leaf, vx_u32 ux, vx_u32 uy, vx_u32 uz, vx_mask m) {
    vx_u32 one = vx_u32_splat(1u);
    vx_u32 i = VX_SV_LEAF_BIT(ux, uy, uz);
    vx_u32 low = vx_gather_masked(blob, m, leaf);
    vx_u32 high = vx_gather_masked(blob, m, leaf + 1u);
    vx_u32 below_bits = (one << VX_SV_LEAF_SHIFT(i)) - 1u;
    return vx_sel(i < 32u, vx_popcount(low & below_bits), vx_popcount(low) + vx_popcount(high & below_bits));
}

/* Depth-first index of the solid voxel at DAG coordinates u in the DAG at `base` (lanes
 * m), from the root down: on every level, the voxels below the siblings before its octant
 * (the node's count below that child: one load, off the path down), plus the bits below its
 * own in the leaf. */
VX_FN vx_u32 vx_sv_dfs_index(VX_BLOB blob, int depth, vx_u32 base, vx_u32 ux, vx_u32 uy, vx_u32 uz, vx_mask m) {
    vx_u32 one = vx_u32_splat(1u);
    vx_u32 node = base + VX_SV_HEADER_WORDS;
    vx_u32 index = vx_u32_splat(0u);
    for (int d = 0; d < depth - VX_SV_LEAF_EDGE_BITS; ++d) {
        vx_u32 octant = VX_SV_OCTANT(ux, uy, uz, vx_u32_splat(vx_i2u(depth - 1 - d)));
        index = index + vx_sv_below_octant(blob, node, octant, m);
        vx_u32 mask = vx_gather_masked(blob, m, node) & VX_SV_NODE_MASK_BITS; /* a cached reload */
        vx_u32 slot = vx_popcount(VX_SV_BELOW(mask, octant, one));
        node = base + vx_gather_masked(blob, m, node + VX_SV_NODE_CHILDREN + slot);
    }
    return index + vx_sv_below_in_leaf(blob, node, ux, uy, uz, m);
}

/* The same for the voxel walk s hit (lanes m, at a leaf), from the nodes on its path: no
 * level's loads wait for the level above. */
VX_FN vx_u32 vx_sv_hit_index(VX_BLOB blob, int depth, vx_sv_state s, vx_u32 ux, vx_u32 uy, vx_u32 uz, vx_mask m) {
    vx_u32 index = vx_u32_splat(0u);
    for (int d = 0; d < depth - VX_SV_LEAF_EDGE_BITS; ++d) {
        vx_u32 octant = VX_SV_OCTANT(ux, uy, uz, vx_u32_splat(vx_i2u(depth - 1 - d)));
        index = index + vx_sv_below_octant(blob, s.path.slot[d], octant, m);
    }
    return index + vx_sv_below_in_leaf(blob, s.node, ux, uy, uz, m);
}

/* The attribute of depth-first index `index` in the DAG at `base`: its payload byte
 * (exact), or the RGBA8 colour of the block holding it (the last block starting at or
 * before it). `kind` is uniform: every DAG a kernel walks has the same attribute kind. */
VX_FN vx_u32 vx_sv_attribute(VX_BLOB blob, uint kind, vx_u32 base, vx_u32 index, vx_mask m) {
    vx_u32 attributes = base + vx_gather_masked(blob, m, base + VX_SV_HEADER_ATTRIBUTES);
    if (kind == VX_SV_ATTRIBUTES_EXACT) {
        vx_u32 word = vx_gather_masked(blob, m, attributes + VX_SV_ATTRIBUTE_WORD(index));
        return (word >> VX_SV_ATTRIBUTE_SHIFT(index)) & 255u;
    }
    vx_u32 count = vx_gather_masked(blob, m, base + VX_SV_HEADER_ATTRIBUTE_COUNT);
    vx_u32 stride = vx_gather_masked(blob, m, base + VX_SV_HEADER_SEARCH_TOP);
    vx_u32 block = vx_u32_splat(0u);
    while (vx_any(m && stride > 0u)) {
        vx_mask inside = m && stride > 0u && block + stride < count;
        vx_u32 start = vx_gather_masked(blob, inside, attributes + block + stride);
        block = vx_sel(inside && start <= index, block + stride, block);
        stride = stride >> 1u;
    }
    return vx_gather_masked(blob, m, base + vx_gather_masked(blob, m, base + VX_SV_HEADER_COLOURS) + block);
}

/* The attribute of the voxel the walk hit, in lanes m. */
VX_FN vx_u32 vx_sv_material(VX_BLOB blob, vx_sv_frame f, uint kind, vx_sv_state s, vx_mask m) {
    vx_u32 ux = vx_i2u(s.w.cx + f.shx) >> s.lod, uy = vx_i2u(s.w.cy + f.shy) >> s.lod,
           uz = vx_i2u(s.w.cz + f.shz) >> s.lod;
    vx_u32 index = vx_sv_hit_index(blob, f.depth, s, ux, uy, uz, m);
    return vx_sel(m, vx_sv_attribute(blob, kind, s.base, index, m), 0u);
}
