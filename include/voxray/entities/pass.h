/* The entity pass of a scene (entities/layout.h): after the world's walk has found its hit
 * (or none), the instances whose boxes the ray meets before it are tested, nearest box
 * first, each by an exact walk of its model in the model's own frame. Shared by every
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
#if !defined(VX_SIMD_WIDTH)

/* Entry t of the ray into node `node`'s box, clipped to [tmin, tmax]; VX_INF when it
 * misses the box or enters after tmax. */
VX_FN float vx_sc_box_enter(VX_BLOB blob, uint node, vx_ray r, float tmax) {
    float lo[3];
    float hi[3];
    for (uint a = 0u; a < 3u; ++a) {
        lo[a] = vx_bits_f(vx_load(blob, node + VX_SC_NODE_MIN + a));
        hi[a] = vx_bits_f(vx_load(blob, node + VX_SC_NODE_MAX + a));
    }
    vx_slab sx = vx_slab_make(r.ox - lo[0], r.dx, hi[0] - lo[0], 1.0f);
    vx_slab sy = vx_slab_make(r.oy - lo[1], r.dy, hi[1] - lo[1], 1.0f);
    vx_slab sz = vx_slab_make(r.oz - lo[2], r.dz, hi[2] - lo[2], 1.0f);
    float tenter = vx_fmax(r.tmin, vx_fmax(sx.t0, vx_fmax(sy.t0, sz.t0)));
    float texit = vx_fmin(tmax, vx_fmin(sx.t1, vx_fmin(sy.t1, sz.t1)));
    return tenter <= texit ? tenter : VX_INF;
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
 * face in the model's own coordinates, the palette index in `material`. */
VX_FN vx_hit vx_sc_model_walk(VX_BLOB blob, uint model, vx_ray q, uint mode) {
    int ex = vx_u2i(vx_load(blob, model + VX_EM_EXTENT + 0));
    int ey = vx_u2i(vx_load(blob, model + VX_EM_EXTENT + 1));
    int ez = vx_u2i(vx_load(blob, model + VX_EM_EXTENT + 2));
    uint bits = model + vx_load(blob, model + VX_EM_BITS);
    vx_dda d = vx_dda_begin_scaled(q, 0.0f, 0.0f, 0.0f, ex, ey, ez, 1.0f);
    while (d.status == VX_STATUS_ACTIVE) {
        uint i = vx_i2u(VX_EM_INDEX(d.cx, d.cy, d.cz, ex, ey));
        bool solid = ((vx_load(blob, bits + (i >> 5u)) >> (i & 31u)) & 1u) != 0u;
        if (solid) d.status = VX_STATUS_HIT;
        else d = vx_dda_advance(d, true, ex, ey, ez);
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

/* `best`: the world's hit for ray r (or its miss). Returns the nearest of it and every
 * instance hit; any-hit returns at the first hit. Steps add the boxes opened and the
 * models' voxel steps. */
VX_FN vx_hit vx_entities_trace(VX_BLOB blob, vx_ray r, vx_hit best, uint mode) {
    uint nodes = vx_load(blob, VX_SC_HEADER_NODES);
    uint items = vx_load(blob, VX_SC_HEADER_ITEMS);
    if (vx_load(blob, VX_SC_HEADER_NODE_COUNT) == 0u) return best;
    if (mode == VX_MODE_ANY && best.status == VX_STATUS_HIT) return best;
    uint best_slot = VX_SC_FREE_SLOT;
    uint pending[VX_SC_MAX_DEPTH];
    int top = 0;
    uint node = 0u;
    while (true) {
        best.steps = best.steps + 1u;
        uint at = nodes + node * VX_SC_NODE_WORDS;
        float tmax = best.status == VX_STATUS_HIT ? best.t : r.tmax;
        bool open = vx_sc_box_enter(blob, at, r, tmax) != VX_INF;
        uint first = vx_load(blob, at + VX_SC_NODE_FIRST);
        uint count = vx_load(blob, at + VX_SC_NODE_COUNT);
        if (open && count == 0u) {
            /* The nearer child first, so the farther one is often culled by then. */
            uint a = nodes + first * VX_SC_NODE_WORDS;
            float ta = vx_sc_box_enter(blob, a, r, tmax);
            float tb = vx_sc_box_enter(blob, a + VX_SC_NODE_WORDS, r, tmax);
            bool b_first = tb < ta;
            pending[top] = b_first ? first : first + 1u;
            top = top + 1;
            node = b_first ? first + 1u : first;
            continue;
        }
        if (open) {
            for (uint k = 0u; k < count; ++k) {
                best = vx_sc_test_instance(blob, vx_load(blob, items + first + k), r, best, VX_ADDR(best_slot), mode);
                if (mode == VX_MODE_ANY && best.status == VX_STATUS_HIT) return best;
            }
        }
        if (top == 0) break;
        top = top - 1;
        node = pending[top];
    }
    return best;
}

#endif /* !VX_SIMD_WIDTH */
