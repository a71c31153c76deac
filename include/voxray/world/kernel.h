/* Traversal of the chunked world (world/layout.h): one walk over the world's voxels that
 * is, per lane, either between chunks (level -1) or inside one chunk's DAG (svdag/walk.h).
 * Between chunks, a step goes down the directory (an octree over the cells) to the region
 * that holds the walk's cell and
 *   - leaves the region at once when it has no voxels;
 *   - leaves the empty slab between the region's wall and the chunk's solid box when the
 *     walk's voxel lies outside that box: the exact form of a ray-box test, which a ray
 *     that misses the box passes in at most three moves and one that hits it ends at
 *     the box;
 *   - else enters the chunk's DAG at its LOD, and walks it in the same step.
 * Inside a DAG, leaving the entry's region pops the walk back between chunks (level -1):
 * a walk never sees a cell through another chunk than the one standing for it. Every move
 * leaves a box that holds the walk's voxel, so the walk ends without a step cap, and every
 * crossing is the spine's exact rule: at LOD 0 the hits are the reference's, bit for bit.
 * Needs prelude.h, ray.h, dda.h, stack.h, bits.h, svdag/walk.h. Included once per lane
 * set; no include guard on purpose. */
#include "voxray/world/layout.h"

VX_STRUCT(vx_world)
    vx_sv_frame f;        /* chunk depth, walk-to-grid shift, the world's size in voxels */
    int ox, oy, oz;       /* world position of walk voxel (0,0,0) */
    int chunk_bits;
    int root_level;
    uint root;
    uint attribute_kind;
VX_END_STRUCT(vx_world)

VX_STRUCT(vx_wd_state)
    vx_sv_state walk;
    vx_u32 region;        /* level of the directory region the lane's chunk stands for */
    vx_u32 only;          /* 0, or the one entry (child word) the walk enters: the frame
                             passes march a ray through one chunk (world/frame/passes.h), and
                             leave every other entry's region as if it were empty */
VX_END_STRUCT(vx_wd_state)

VX_FN vx_world vx_world_load(VX_BLOB blob) {
    vx_world g;
    g.ox = vx_u2i(vx_load(blob, VX_WD_HEADER_ORIGIN + 0));
    g.oy = vx_u2i(vx_load(blob, VX_WD_HEADER_ORIGIN + 1));
    g.oz = vx_u2i(vx_load(blob, VX_WD_HEADER_ORIGIN + 2));
    g.f.ex = vx_u2i(vx_load(blob, VX_WD_HEADER_EXTENT + 0));
    g.f.ey = vx_u2i(vx_load(blob, VX_WD_HEADER_EXTENT + 1));
    g.f.ez = vx_u2i(vx_load(blob, VX_WD_HEADER_EXTENT + 2));
    g.f.shx = vx_u2i(vx_load(blob, VX_WD_HEADER_SHIFT + 0));
    g.f.shy = vx_u2i(vx_load(blob, VX_WD_HEADER_SHIFT + 1));
    g.f.shz = vx_u2i(vx_load(blob, VX_WD_HEADER_SHIFT + 2));
    g.chunk_bits = vx_u2i(vx_load(blob, VX_WD_HEADER_CHUNK_BITS));
    g.f.depth = g.chunk_bits;
    g.root_level = vx_u2i(vx_load(blob, VX_WD_HEADER_ROOT_LEVEL));
    g.root = vx_load(blob, VX_WD_HEADER_ROOT);
    g.attribute_kind = vx_load(blob, VX_WD_HEADER_ATTRIBUTE_KIND);
    return g;
}

VX_FN vx_wd_state vx_world_begin(vx_world g, vx_ray r) {
    vx_wd_state st;
    st.walk = vx_sv_begin(g.f, r, g.ox, g.oy, g.oz);
    st.region = vx_u32_splat(0u);
    st.only = vx_u32_splat(0u);
    return st;
}

VX_FN vx_u32 vx_wd_min(vx_u32 a, vx_u32 b) { return vx_sel(a < b, a, b); }
VX_FN vx_u32 vx_wd_max(vx_u32 a, vx_u32 b) { return vx_sel(a > b, a, b); }

/* One step of every live lane: between chunks, the directory (see the top comment);
 * then, for lanes in a DAG (those that just entered one too), one DAG step. */
VX_FN vx_wd_state vx_world_step(VX_BLOB blob, vx_world g, vx_wd_state st) {
    vx_sv_state s = st.walk;
    vx_mask live = s.w.status == VX_STATUS_ACTIVE;
    vx_mask between = live && s.level < 0;
    vx_mask moved = between && !between; /* no lane */
    vx_u32 gx = vx_i2u(s.w.cx + g.f.shx), gy = vx_i2u(s.w.cy + g.f.shy), gz = vx_i2u(s.w.cz + g.f.shz);
    if (vx_any(between)) {
        /* Down the directory to the region holding the walk's cell: an entry, or no voxels. */
        vx_u32 node = vx_u32_splat(g.root);
        vx_u32 found = vx_u32_splat(0u);
        vx_u32 region = vx_u32_splat(0u);
        vx_mask searching = between;
        for (int level = g.root_level; level > 0; --level) {
            if (!vx_any(searching)) break;
            vx_u32 octant = VX_SV_OCTANT(gx, gy, gz, vx_u32_splat(vx_i2u(g.chunk_bits + level - 1)));
            vx_u32 child = vx_gather_masked(blob, searching, node + octant);
            vx_mask stop = searching && (child == 0u || (child & VX_WD_CHILD_IS_ENTRY) != 0u);
            found = vx_sel(stop, child, found);
            region = vx_sel(stop, vx_u32_splat(vx_i2u(level - 1)), region);
            node = vx_sel(searching && !stop, child, node);
            searching = searching && !stop;
        }
        vx_mask present = between && found != 0u && (st.only == 0u || found == st.only);
        vx_u32 entry = found - VX_WD_CHILD_IS_ENTRY;
        vx_u32 dag = vx_gather_masked(blob, present, entry + VX_WD_ENTRY_DAG);
        vx_u32 lod = vx_gather_masked(blob, present, entry + VX_WD_ENTRY_LOD);
        vx_u32 box_min = vx_gather_masked(blob, present, entry + VX_WD_ENTRY_BOX_MIN);
        vx_u32 box_max = vx_gather_masked(blob, present, entry + VX_WD_ENTRY_BOX_MAX);
        /* The region and the chunk in grid voxels, and the walk's voxel in the chunk's DAG voxels. */
        vx_u32 edge = vx_u32_splat(1u << g.chunk_bits);
        vx_u32 size = edge << region, chunk_size = edge << lod;
        vx_u32 rx = gx & (0u - size), ry = gy & (0u - size), rz = gz & (0u - size);
        vx_u32 cx = gx & (0u - chunk_size), cy = gy & (0u - chunk_size), cz = gz & (0u - chunk_size);
        vx_u32 lx = (gx - cx) >> lod, ly = (gy - cy) >> lod, lz = (gz - cz) >> lod;
        vx_u32 minx = VX_WD_BOX_X(box_min), miny = VX_WD_BOX_Y(box_min), minz = VX_WD_BOX_Z(box_min);
        vx_u32 maxx = VX_WD_BOX_X(box_max), maxy = VX_WD_BOX_Y(box_max), maxz = VX_WD_BOX_Z(box_max);
        vx_mask out_x = lx < minx || lx > maxx, out_y = ly < miny || ly > maxy, out_z = lz < minz || lz > maxz;
        vx_mask enter = present && !out_x && !out_y && !out_z;
        /* The empty box to leave: the region (no voxels), or the part of the region on the
         * near side of the solid box on the first axis the voxel is outside it on. */
        vx_u32 lox = rx, loy = ry, loz = rz, hix = rx + size, hiy = ry + size, hiz = rz + size;
        vx_mask sx = present && out_x, sy = present && !out_x && out_y, sz = present && !out_x && !out_y && out_z;
        hix = vx_sel(sx && lx < minx, vx_wd_min(hix, cx + (minx << lod)), hix);
        lox = vx_sel(sx && lx > maxx, vx_wd_max(lox, cx + ((maxx + 1u) << lod)), lox);
        hiy = vx_sel(sy && ly < miny, vx_wd_min(hiy, cy + (miny << lod)), hiy);
        loy = vx_sel(sy && ly > maxy, vx_wd_max(loy, cy + ((maxy + 1u) << lod)), loy);
        hiz = vx_sel(sz && lz < minz, vx_wd_min(hiz, cz + (minz << lod)), hiz);
        loz = vx_sel(sz && lz > maxz, vx_wd_max(loz, cz + ((maxz + 1u) << lod)), loz);
        moved = between && !enter;
        s = vx_sv_leave(g.f, s, vx_u2i(lox) - g.f.shx, vx_u2i(loy) - g.f.shy, vx_u2i(loz) - g.f.shz,
                        vx_u2i(hix) - g.f.shx, vx_u2i(hiy) - g.f.shy, vx_u2i(hiz) - g.f.shz, moved);
        s = vx_sv_enter(s, dag, lod, enter);
        st.region = vx_sel(enter, region, st.region);
    }
    s = vx_sv_step(blob, g.f, s, live && !moved && s.level >= 0);
    /* A walk that leaves its region goes back to the directory (the DAG step already
     * popped those that left the chunk; this catches a part of a coarser chunk). */
    vx_u32 apart = (vx_i2u(s.w.cx + g.f.shx) ^ gx) | (vx_i2u(s.w.cy + g.f.shy) ^ gy) | (vx_i2u(s.w.cz + g.f.shz) ^ gz);
    vx_mask left = (apart >> (vx_u32_splat(vx_i2u(g.chunk_bits)) + st.region)) != 0u;
    s.level = vx_sel(left && s.level >= 0, -1, s.level);
    st.walk = s;
    return st;
}

VX_FN vx_u32 vx_world_status(vx_wd_state st) { return st.walk.w.status; }

/* The hit record; any-hit (a constant `mode`) skips the attribute lookup. A hit on a
 * coarse chunk reports the walk voxel it entered the coarse voxel through. */
VX_FN vx_hit vx_world_finish(VX_BLOB blob, vx_world g, vx_wd_state st, vx_ray r, uint mode) {
    VX_UNUSED(r);
    vx_mask is_hit = st.walk.w.status == VX_STATUS_HIT;
    vx_u32 material = vx_u32_splat(0u);
    if (mode == VX_MODE_CLOSEST) material = vx_sv_material(blob, g.f, g.attribute_kind, st.walk, is_hit);
    return vx_hit_from_walk(st.walk.w, g.ox, g.oy, g.oz, material);
}

/* Closest hit, or any hit (the first solid voxel serves both; any-hit skips attributes). */
VX_FN vx_hit vx_world_trace(VX_BLOB blob, vx_ray r, uint mode) {
    vx_world g = vx_world_load(blob);
    vx_wd_state st = vx_world_begin(g, r);
    while (vx_any(st.walk.w.status == VX_STATUS_ACTIVE)) st = vx_world_step(blob, g, st);
    return vx_world_finish(blob, g, st, r, mode);
}
