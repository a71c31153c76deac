/* The entity pass of a scene (entities/layout.h): after the world's walk has found its hit
 * (or none), the instances whose boxes the ray meets before it are tested, each by an exact
 * walk of its model in the model's own frame. They are found by the BVH (nearest box first)
 * or, where the scene keeps them, by the chunk lists (chunks in ray order). Shared by every
 * scene kernel (entities/scene_kernel.h), so it is part of the dialect (kernels/dialect.h).
 *
 * One ray a call, scalar code: each ray meets its own instances, so SIMD lanes would
 * diverge at once. GPU work-items and the C++ scalar lanes run it directly; the C++ SIMD
 * lanes run it lane by lane (vx_each_lane, cpu/simd_lanes.inc), which is why it is compiled
 * only where lanes are scalar.
 *
 * Exact and uncapped: every box the ray meets before the best hit so far is opened (the
 * stack holds one node a level, and the host keeps the tree within VX_SC_MAX_DEPTH levels);
 * every model walk runs to its end. Ties: the world wins over an instance at the same t, and
 * among instances the lower slot wins, so the result does not depend on the visiting order. */
/* Per lane: whether the ray enters the box of all instances (the BVH's root) before its hit
 * `h` (the world's). Written for every lane set: the C++ SIMD lanes run the scalar pass lane
 * by lane only where this holds, so rays that pass no entity cost a few vector operations
 * (the scalar pass begins with the same test). */
VX_FN vx_mask vx_sc_enters_entities(VX_BLOB blob, vx_ray r, vx_hit h) {
    uint root = vx_load(blob, VX_SC_HEADER_NODES);
    float limit = vx_load(blob, VX_SC_HEADER_NODE_COUNT) != 0u ? VX_INF : -VX_INF;  /* no instances: none */
    vx_f32 t0 = r.tmin;
    vx_f32 t1 = vx_fmin(vx_sel(h.status == VX_STATUS_HIT, h.t, r.tmax), vx_f32_splat(limit));
    vx_f32 o[3];
    vx_f32 d[3];
    o[0] = r.ox; o[1] = r.oy; o[2] = r.oz;
    d[0] = r.dx; d[1] = r.dy; d[2] = r.dz;
    for (uint a = 0u; a < 3u; ++a) {
        float lo = vx_bits_f(vx_load(blob, root + VX_SC_NODE_MIN + a));
        float hi = vx_bits_f(vx_load(blob, root + VX_SC_NODE_MAX + a));
        vx_mask moving = vx_moves(d[a]);
        vx_f32 inv = 1.0f / vx_sel(moving, d[a], vx_f32_splat(1.0f));
        vx_f32 ta = (lo - o[a]) * inv;
        vx_f32 tb = (hi - o[a]) * inv;
        t0 = vx_sel(moving, vx_fmax(t0, vx_fmin(ta, tb)), t0);
        vx_mask inside = o[a] >= lo && o[a] <= hi;
        t1 = vx_sel(moving, vx_fmin(t1, vx_fmax(ta, tb)), vx_sel(inside, t1, vx_f32_splat(-VX_INF)));
    }
    return t0 <= t1;
}

#if !defined(VX_SIMD_WIDTH)

/* What every box test of one ray needs, computed once: 1/d per axis (0 on an axis the ray
 * does not move along, vx_moves), and the ray itself. */
VX_STRUCT(vx_sc_box_ray)
    vx_ray r;
    float ix, iy, iz;
VX_END_STRUCT(vx_sc_box_ray)

VX_FN vx_sc_box_ray vx_sc_box_ray_make(vx_ray r) {
    vx_sc_box_ray b;
    b.r = r;
    b.ix = vx_moves(r.dx) ? 1.0f / r.dx : 0.0f;
    b.iy = vx_moves(r.dy) ? 1.0f / r.dy : 0.0f;
    b.iz = vx_moves(r.dz) ? 1.0f / r.dz : 0.0f;
    return b;
}

/* One axis: narrows [t0, t1] to where the ray lies between lo and hi; an axis the ray does not
 * move along keeps it where the origin lies between them, else empties it. */
VX_FN void vx_sc_slab(float o, float inv, float lo, float hi, VX_INOUT(float) t0, VX_INOUT(float) t1) {
    if (inv == 0.0f) {
        if (!(o >= lo && o <= hi)) VX_REF(t1) = -VX_INF;
        return;
    }
    float ta = (lo - o) * inv;
    float tb = (hi - o) * inv;
    VX_REF(t0) = vx_fmax(VX_REF(t0), vx_fmin(ta, tb));
    VX_REF(t1) = vx_fmin(VX_REF(t1), vx_fmax(ta, tb));
}

/* Entry t of the ray into the box at word `node` (a BVH node's, or an instance's in the chunk
 * lists: min x, y, z, max x, y, z), clipped to [tmin, tmax]; VX_INF when it misses the box
 * or enters after tmax. (Boxes carry a margin for rounding, placed_box.) */
VX_FN float vx_sc_box_enter(VX_BLOB blob, uint node, vx_sc_box_ray b, float tmax) {
    float t0 = b.r.tmin;
    float t1 = tmax;
    vx_sc_slab(b.r.ox, b.ix, vx_bits_f(vx_load(blob, node + VX_SC_NODE_MIN + 0u)),
               vx_bits_f(vx_load(blob, node + VX_SC_NODE_MAX + 0u)), VX_ADDR(t0), VX_ADDR(t1));
    vx_sc_slab(b.r.oy, b.iy, vx_bits_f(vx_load(blob, node + VX_SC_NODE_MIN + 1u)),
               vx_bits_f(vx_load(blob, node + VX_SC_NODE_MAX + 1u)), VX_ADDR(t0), VX_ADDR(t1));
    vx_sc_slab(b.r.oz, b.iz, vx_bits_f(vx_load(blob, node + VX_SC_NODE_MIN + 2u)),
               vx_bits_f(vx_load(blob, node + VX_SC_NODE_MAX + 2u)), VX_ADDR(t0), VX_ADDR(t1));
    return t0 <= t1 ? t0 : VX_INF;
}

/* The ray in the frame of the instance whose words start at `inst`, up to tmax. */
VX_FN vx_ray vx_sc_model_ray(VX_BLOB blob, uint inst, vx_ray r, float tmax) {
    float m[VX_SC_INSTANCE_WORDS];
    for (uint k = 0u; k < VX_SC_INSTANCE_MODEL; ++k) m[k] = vx_bits_f(vx_load(blob, inst + k));
    vx_ray q;
    VX_PRECISE float ox = VX_SC_TO_MODEL(m, 0, r.ox, r.oy, r.oz);
    VX_PRECISE float oy = VX_SC_TO_MODEL(m, 1, r.ox, r.oy, r.oz);
    VX_PRECISE float oz = VX_SC_TO_MODEL(m, 2, r.ox, r.oy, r.oz);
    VX_PRECISE float dx = VX_SC_DIR_TO_MODEL(m, 0, r.dx, r.dy, r.dz);
    VX_PRECISE float dy = VX_SC_DIR_TO_MODEL(m, 1, r.dx, r.dy, r.dz);
    VX_PRECISE float dz = VX_SC_DIR_TO_MODEL(m, 2, r.dx, r.dy, r.dz);
    q.ox = ox; q.oy = oy; q.oz = oz;
    q.dx = dx; q.dy = dy; q.dz = dz;
    q.tmin = r.tmin;
    q.tmax = tmax;
    return q;
}

/* The first solid voxel of the model record at `model` along model-frame ray q: voxel and
 * face in the model's own coordinates, the palette index in `material`. In a brick with a
 * solid voxel the walk steps voxel by voxel; an empty brick's field (entities/layout.h)
 * names an empty cuboid of bricks around it, which the walk leaves in one move at the
 * voxel the voxel-by-voxel walk would reach (vx_dda_leave_box). */
VX_FN vx_hit vx_sc_model_walk(VX_BLOB blob, uint model, vx_ray q, uint mode) {
    int ex = vx_u2i(vx_load(blob, model + VX_EM_EXTENT + 0));
    int ey = vx_u2i(vx_load(blob, model + VX_EM_EXTENT + 1));
    int ez = vx_u2i(vx_load(blob, model + VX_EM_EXTENT + 2));
    uint bits = model + vx_load(blob, model + VX_EM_BITS);
    uint fields = vx_load(blob, model + VX_EM_BRICKS);
    uint bricks = model + fields;
    int bx = (ex + (VX_EM_BRICK_EDGE - 1)) >> VX_EM_BRICK_SHIFT;
    int by = (ey + (VX_EM_BRICK_EDGE - 1)) >> VX_EM_BRICK_SHIFT;
    vx_dda d = vx_dda_begin_scaled(q, 0.0f, 0.0f, 0.0f, ex, ey, ez, 1.0f);
    /* The brick word last read (consecutive voxels mostly share a brick); a record with no
     * fields reads as all bricks solid. */
    int read_at = -1;
    uint brick = VX_EM_BRICK_SOLID;
    while (d.status == VX_STATUS_ACTIVE) {
        int b = (d.cx >> VX_EM_BRICK_SHIFT) + bx * ((d.cy >> VX_EM_BRICK_SHIFT) + by * (d.cz >> VX_EM_BRICK_SHIFT));
        if (fields != 0u && b != read_at) {
            brick = vx_load(blob, bricks + vx_i2u(b));
            read_at = b;
        }
        if ((brick & VX_EM_BRICK_SOLID) != 0u) {
            uint i = vx_i2u(VX_EM_INDEX(d.cx, d.cy, d.cz, ex, ey));
            bool solid = ((vx_load(blob, bits + (i >> 5u)) >> (i & 31u)) & 1u) != 0u;
            if (solid) d.status = VX_STATUS_HIT;
            else d = vx_dda_advance(d, true, ex, ey, ez);
            continue;
        }
        /* The empty cuboid, in voxels, cut at the model's box (its last bricks may stick out). */
        int lx = ((d.cx >> VX_EM_BRICK_SHIFT) - vx_u2i(VX_EM_FIELD(brick, 1u))) << VX_EM_BRICK_SHIFT;
        int ly = ((d.cy >> VX_EM_BRICK_SHIFT) - vx_u2i(VX_EM_FIELD(brick, 3u))) << VX_EM_BRICK_SHIFT;
        int lz = ((d.cz >> VX_EM_BRICK_SHIFT) - vx_u2i(VX_EM_FIELD(brick, 5u))) << VX_EM_BRICK_SHIFT;
        int hx = ((d.cx >> VX_EM_BRICK_SHIFT) + vx_u2i(VX_EM_FIELD(brick, 0u)) + 1) << VX_EM_BRICK_SHIFT;
        int hy = ((d.cy >> VX_EM_BRICK_SHIFT) + vx_u2i(VX_EM_FIELD(brick, 2u)) + 1) << VX_EM_BRICK_SHIFT;
        int hz = ((d.cz >> VX_EM_BRICK_SHIFT) + vx_u2i(VX_EM_FIELD(brick, 4u)) + 1) << VX_EM_BRICK_SHIFT;
        d = vx_dda_leave_box(d, q.dx, q.dy, q.dz, lx, ly, lz, hx < ex ? hx : ex, hy < ey ? hy : ey, hz < ez ? hz : ez, true);
        if (d.cx < 0 || d.cy < 0 || d.cz < 0 || d.cx >= ex || d.cy >= ey || d.cz >= ez) d.status = VX_STATUS_MISS;
    }
    uint material = 0u;
    if (mode == VX_MODE_CLOSEST && d.status == VX_STATUS_HIT) {
        uint i = vx_i2u(VX_EM_INDEX(d.cx, d.cy, d.cz, ex, ey));
        uint word = vx_load(blob, model + vx_load(blob, model + VX_EM_MATERIALS) + (i >> 2u));
        material = (word >> ((i & 3u) * 8u)) & 255u;
    }
    return vx_hit_from_walk(d, vx_u2i(vx_load(blob, model + VX_EM_MIN + 0)), vx_u2i(vx_load(blob, model + VX_EM_MIN + 1)),
                            vx_u2i(vx_load(blob, model + VX_EM_MIN + 2)), material);
}

/* The instance of `slot` tested against the best hit so far (`best_slot`: the slot of an
 * instance best is on, or VX_SC_FREE_SLOT for the world or none). */
VX_FN vx_hit vx_sc_test_instance(VX_BLOB blob, uint slot, vx_ray r, vx_hit best, VX_INOUT(uint) best_slot, uint mode) {
    uint inst = vx_load(blob, VX_SC_HEADER_INSTANCES) + slot * VX_SC_INSTANCE_WORDS;
    uint model = vx_load(blob, inst + VX_SC_INSTANCE_MODEL);
    float tmax = best.status == VX_STATUS_HIT ? best.t : r.tmax;
    vx_hit h = vx_sc_model_walk(blob, model, vx_sc_model_ray(blob, inst, r, tmax), mode);
    best.steps = best.steps + h.steps;
    bool better = h.status == VX_STATUS_HIT &&
                  (best.status != VX_STATUS_HIT || h.t < best.t ||
                   (h.t == best.t && VX_REF(best_slot) != VX_SC_FREE_SLOT && slot < VX_REF(best_slot)));
    if (better) {
        uint steps = best.steps;
        best = h;
        best.steps = steps;
        best.material = h.material | ((slot + 1u) << VX_SC_INSTANCE_SHIFT);
        VX_REF(best_slot) = slot;
    }
    return best;
}

/* The chunk lists' way to the same answer as vx_entities_trace (entities/layout.h): the
 * ray walks the 16^3 chunks of the lists' grid in order, up to the best hit so far, and
 * tests each instance of a chunk's list whose world box it enters in that chunk (so an
 * instance once a ray, however many chunks it spans). After a chunk, a hit before the
 * chunk's far side ends the walk: every instance not yet tested is entered beyond it.
 * Steps add a chunk each. */
VX_FN vx_hit vx_entities_trace_chunks(VX_BLOB blob, uint lists, vx_ray r, vx_hit best, uint mode) {
    int nx = vx_u2i(vx_load(blob, lists + VX_SC_CHUNK_SIZE + 0u));
    int ny = vx_u2i(vx_load(blob, lists + VX_SC_CHUNK_SIZE + 1u));
    int nz = vx_u2i(vx_load(blob, lists + VX_SC_CHUNK_SIZE + 2u));
    vx_ray c = r;
    c.tmax = best.status == VX_STATUS_HIT ? best.t : r.tmax;
    vx_dda d = vx_dda_begin_scaled(c, vx_i2f(vx_u2i(vx_load(blob, lists + VX_SC_CHUNK_MIN + 0u))),
                                   vx_i2f(vx_u2i(vx_load(blob, lists + VX_SC_CHUNK_MIN + 1u))),
                                   vx_i2f(vx_u2i(vx_load(blob, lists + VX_SC_CHUNK_MIN + 2u))), nx, ny, nz,
                                   vx_i2f(VX_SC_CHUNK_EDGE));
    uint chunks = lists + vx_load(blob, lists + VX_SC_CHUNK_WORDS);
    vx_sc_box_ray b = vx_sc_box_ray_make(r);
    uint best_slot = VX_SC_FREE_SLOT;
    /* The first chunk also takes instances entered before it (by rounding at the grid's side). */
    float enter_from = -VX_INF;
    while (d.status == VX_STATUS_ACTIVE) {
        best.steps = best.steps + 1u;
        float leave = vx_fmin(d.nx, vx_fmin(d.ny, d.nz));
        uint list = vx_load(blob, chunks + vx_i2u(d.cx + nx * (d.cy + ny * d.cz)));
        if (list != 0u) {
            uint count = vx_load(blob, lists + list);
            for (uint k = 0u; k < count; ++k) {
                uint slot = vx_load(blob, lists + list + 1u + k);
                float tmax = best.status == VX_STATUS_HIT ? best.t : r.tmax;
                float enter = vx_sc_box_enter(blob, lists + VX_SC_CHUNK_BOXES + slot * VX_SC_CHUNK_BOX_WORDS, b, tmax);
                if (!(enter >= enter_from && enter < leave)) continue;
                best = vx_sc_test_instance(blob, slot, r, best, VX_ADDR(best_slot), mode);
                if (mode == VX_MODE_ANY && best.status == VX_STATUS_HIT) return best;
            }
        }
        /* A hit exactly on the far side waits: an instance entered there may tie with a lower slot. */
        if (best.status == VX_STATUS_HIT && best.t < leave) break;
        enter_from = leave;
        d = vx_dda_advance(d, true, nx, ny, nz);
    }
    return best;
}

/* `best`: the world's hit for ray r (or its miss). Returns the nearest of it and every
 * instance hit; any-hit returns at the first hit. Steps add the boxes opened and the
 * models' voxel steps. */
VX_FN vx_hit vx_entities_trace(VX_BLOB blob, vx_ray r, vx_hit best, uint mode) {
    uint nodes = vx_load(blob, VX_SC_HEADER_NODES);
    uint items = vx_load(blob, VX_SC_HEADER_ITEMS);
    if (vx_load(blob, VX_SC_HEADER_NODE_COUNT) == 0u) return best;
    if (mode == VX_MODE_ANY && best.status == VX_STATUS_HIT) return best;
    uint lists = vx_load(blob, VX_SC_HEADER_CHUNKS);
    if (lists != 0u) return vx_entities_trace_chunks(blob, lists, r, best, mode);
    vx_sc_box_ray b = vx_sc_box_ray_make(r);
    uint best_slot = VX_SC_FREE_SLOT;
    /* Nodes whose box the ray enters, with the entry t, still to visit: one a level. */
    uint pending[VX_SC_MAX_DEPTH];
    float pending_t[VX_SC_MAX_DEPTH];
    int top = 0;
    best.steps = best.steps + 1u;
    float t = vx_sc_box_enter(blob, nodes, b, best.status == VX_STATUS_HIT ? best.t : r.tmax);
    uint node = 0u;
    bool open = t != VX_INF;
    while (true) {
        if (open) {
            uint at = nodes + node * VX_SC_NODE_WORDS;
            uint first = vx_load(blob, at + VX_SC_NODE_FIRST);
            uint count = vx_load(blob, at + VX_SC_NODE_COUNT);
            if (count == 0u) {
                /* Both children's boxes, the nearer visited first and the farther kept (a miss
                 * is dropped): by the time it is taken, the best hit may cull it. */
                float tmax = best.status == VX_STATUS_HIT ? best.t : r.tmax;
                float ta = vx_sc_box_enter(blob, nodes + first * VX_SC_NODE_WORDS, b, tmax);
                float tb = vx_sc_box_enter(blob, nodes + (first + 1u) * VX_SC_NODE_WORDS, b, tmax);
                best.steps = best.steps + 2u;
                bool b_first = tb < ta;
                float near_t = b_first ? tb : ta;
                float far_t = b_first ? ta : tb;
                if (far_t != VX_INF) {
                    pending[top] = b_first ? first : first + 1u;
                    pending_t[top] = far_t;
                    top = top + 1;
                }
                node = b_first ? first + 1u : first;
                open = near_t != VX_INF;
                continue;
            }
            for (uint k = 0u; k < count; ++k) {
                best = vx_sc_test_instance(blob, vx_load(blob, items + first + k), r, best, VX_ADDR(best_slot), mode);
                if (mode == VX_MODE_ANY && best.status == VX_STATUS_HIT) return best;
            }
        }
        if (top == 0) break;
        top = top - 1;
        node = pending[top];
        /* Entered before the best hit so far (ties included: a lower slot may still win)? */
        open = best.status != VX_STATUS_HIT || pending_t[top] <= best.t;
    }
    return best;
}

#endif /* !VX_SIMD_WIDTH */
