/* The GPU-driven passes over a chunked world (the paper's section 3.5), in the portable
 * dialect: one item per invocation (scalar lanes on the CPU), every pass a function of
 * (world blob, frame words, item). The host (world/frame/frame.hpp) runs them in this order:
 *
 *   clear            pixels      visibility and material words to 0
 *   select chunks    table rows  frustum culling: a chunk's box projected to a tile rect
 *                                (the whole screen when the camera is in front of none of
 *                                its corners' depth), and its near key
 *   select tiles     visible x   tile-chunk pairs whose near key is not behind the previous
 *                    tile rows   frame's Hi-Z
 *   march            pairs x 64  each pixel of the tile through that chunk only; the hit
 *                                enters the visibility buffer by 64-bit atomic max
 *   build Hi-Z       tiles       per tile the farthest key of its pixels
 *   select again     visible x   the pairs the previous Hi-Z culled that this frame's passes
 *                    tile rows
 *   march            pairs x 64
 *   build Hi-Z       tiles       (next frame's previous)
 *   resolve          pixels      chunk id and voxel -> DFS index -> attribute (colour block)
 *
 * The chunk that holds the camera (the paper's self chunk) has its near depth at 0, so no
 * Hi-Z ever culls it: the paper traces its DAG during tile selection to learn a nearer
 * bound, which costs what marching it costs. Every hit is the one the world's own trace
 * finds through that chunk (the same walk, restricted to one entry, world/kernel.h), and
 * culling only drops pairs whose every pixel is already nearer, so the nearest hit per
 * pixel is the trace's.
 * Needs world/kernel.h and what it needs. Included once (scalar lanes); no include guard. */
#include "voxray/world/frame/layout.h"

#if defined(VX_DIALECT_OPENCL)
#pragma OPENCL EXTENSION cl_khr_int64_base_atomics : enable
#pragma OPENCL EXTENSION cl_khr_int64_extended_atomics : enable
#endif

VX_STRUCT(vx_wf_view)
    float cx, cy, cz;     /* camera */
    float fx, fy, fz;     /* F */
    float rx, ry, rz;     /* R */
    float ux, uy, uz;     /* U */
    float sx, sy;         /* 2 / width, 2 / height */
    float depth_scale;
    int width, height, tiles_x, tiles_y;
VX_END_STRUCT(vx_wf_view)

VX_FN float vx_wf_float(VX_FRAME f, uint i) { return vx_bits_f(vx_frame_load(f, i)); }

VX_FN vx_wf_view vx_wf_load_view(VX_FRAME f) {
    vx_wf_view v;
    v.cx = vx_wf_float(f, VX_WF_HEADER_CAMERA + 0u);
    v.cy = vx_wf_float(f, VX_WF_HEADER_CAMERA + 1u);
    v.cz = vx_wf_float(f, VX_WF_HEADER_CAMERA + 2u);
    v.fx = vx_wf_float(f, VX_WF_HEADER_FORWARD + 0u);
    v.fy = vx_wf_float(f, VX_WF_HEADER_FORWARD + 1u);
    v.fz = vx_wf_float(f, VX_WF_HEADER_FORWARD + 2u);
    v.rx = vx_wf_float(f, VX_WF_HEADER_RIGHT + 0u);
    v.ry = vx_wf_float(f, VX_WF_HEADER_RIGHT + 1u);
    v.rz = vx_wf_float(f, VX_WF_HEADER_RIGHT + 2u);
    v.ux = vx_wf_float(f, VX_WF_HEADER_UP + 0u);
    v.uy = vx_wf_float(f, VX_WF_HEADER_UP + 1u);
    v.uz = vx_wf_float(f, VX_WF_HEADER_UP + 2u);
    v.sx = vx_wf_float(f, VX_WF_HEADER_PIXEL_SCALE + 0u);
    v.sy = vx_wf_float(f, VX_WF_HEADER_PIXEL_SCALE + 1u);
    v.depth_scale = vx_wf_float(f, VX_WF_HEADER_DEPTH_SCALE);
    v.width = vx_u2i(vx_frame_load(f, VX_WF_HEADER_WIDTH));
    v.height = vx_u2i(vx_frame_load(f, VX_WF_HEADER_HEIGHT));
    v.tiles_x = vx_u2i(vx_frame_load(f, VX_WF_HEADER_TILES_X));
    v.tiles_y = vx_u2i(vx_frame_load(f, VX_WF_HEADER_TILES_Y));
    return v;
}

/* The ray of pixel (px, py) (frame/layout.h). Two roundings per product and sum on every
 * backend (no contraction), so the host's rays for the same pixel are these, bit for bit. */
VX_FN vx_ray vx_wf_pixel_ray(vx_wf_view v, int px, int py) {
    VX_PRECISE float a = (vx_i2f(px) + 0.5f) * v.sx - 1.0f;
    VX_PRECISE float b = 1.0f - (vx_i2f(py) + 0.5f) * v.sy;
    VX_PRECISE float dx = v.fx + a * v.rx + b * v.ux;
    VX_PRECISE float dy = v.fy + a * v.ry + b * v.uy;
    VX_PRECISE float dz = v.fz + a * v.rz + b * v.uz;
    vx_ray r;
    r.ox = v.cx; r.oy = v.cy; r.oz = v.cz; r.tmin = 0.0f;
    r.dx = dx; r.dy = dy; r.dz = dz; r.tmax = VX_INF;
    return r;
}

/* 2^24 - 1 at depth 0 down to 0 at the far plane and beyond (frame/layout.h). */
VX_FN uint vx_wf_depth_key(float depth, float scale) {
    float q = vx_fmax(vx_fmin(depth * scale, 16777215.0f), 0.0f);
    return VX_WF_DEPTH_MAX - vx_i2u(vx_f2i(q));
}

/* World position of the walk's voxel (0,0,0), as floats. */
VX_FN float vx_wf_origin(VX_BLOB blob, uint axis) { return vx_i2f(vx_u2i(vx_load(blob, VX_WD_HEADER_ORIGIN + axis))); }
VX_FN uint vx_wf_row(VX_BLOB blob, uint i) { return vx_load(blob, VX_WD_HEADER_TABLE) + i * VX_WD_ROW_WORDS; }
VX_FN float vx_wf_box(VX_BLOB blob, uint row, uint word, uint axis) {
    return vx_i2f(vx_u2i(vx_load(blob, row + word + axis))) + vx_wf_origin(blob, axis);
}

VX_FN void vx_wf_clear(VX_FRAME f, uint pixel) {
    uint pixels = vx_frame_load(f, VX_WF_HEADER_WIDTH) * vx_frame_load(f, VX_WF_HEADER_HEIGHT);
    if (pixel >= pixels) return;
    uint at = vx_frame_load(f, VX_WF_HEADER_VISIBILITY_AT) + 2u * pixel;
    vx_frame_store(f, at, 0u);
    vx_frame_store(f, at + 1u, 0u);
    vx_frame_store(f, vx_frame_load(f, VX_WF_HEADER_MATERIAL_AT) + pixel, 0u);
}

/* Frustum culling of table row i: its box's corners projected to pixels give a rect
 * (widened by a pixel for rounding); a corner at or behind the camera plane makes it the
 * whole screen. Boxes wholly behind the camera, beyond the far plane or off screen go. */
VX_FN void vx_wf_select_chunk(VX_BLOB blob, VX_FRAME f, uint i) {
    if (i >= vx_load(blob, VX_WD_HEADER_TABLE_ROWS)) return;
    vx_wf_view v = vx_wf_load_view(f);
    uint row = vx_wf_row(blob, i);
    float rr = v.rx * v.rx + v.ry * v.ry + v.rz * v.rz, uu = v.ux * v.ux + v.uy * v.uy + v.uz * v.uz;
    float zmin = VX_INF, zmax = -VX_INF;
    float pxmin = VX_INF, pxmax = -VX_INF, pymin = VX_INF, pymax = -VX_INF;
    bool whole_screen = false;
    for (uint c = 0u; c < 8u; ++c) {
        float x = vx_wf_box(blob, row, (c & 1u) != 0u ? VX_WD_ROW_MAX : VX_WD_ROW_MIN, 0u) - v.cx;
        float y = vx_wf_box(blob, row, (c & 2u) != 0u ? VX_WD_ROW_MAX : VX_WD_ROW_MIN, 1u) - v.cy;
        float z = vx_wf_box(blob, row, (c & 4u) != 0u ? VX_WD_ROW_MAX : VX_WD_ROW_MIN, 2u) - v.cz;
        float depth = x * v.fx + y * v.fy + z * v.fz;
        zmin = vx_fmin(zmin, depth);
        zmax = vx_fmax(zmax, depth);
        if (depth <= 0.001f) {
            whole_screen = true;
        } else {
            float a = (x * v.rx + y * v.ry + z * v.rz) / (depth * rr);
            float b = (x * v.ux + y * v.uy + z * v.uz) / (depth * uu);
            float px = (a + 1.0f) / v.sx - 0.5f, py = (1.0f - b) / v.sy - 0.5f;
            pxmin = vx_fmin(pxmin, px);
            pxmax = vx_fmax(pxmax, px);
            pymin = vx_fmin(pymin, py);
            pymax = vx_fmax(pymax, py);
        }
    }
    if (zmax <= 0.0f || vx_wf_depth_key(zmin - 1.0f, v.depth_scale) == 0u) return;
    float w = vx_i2f(v.width - 1), h = vx_i2f(v.height - 1);
    if (whole_screen) {
        pxmin = 0.0f; pymin = 0.0f; pxmax = w; pymax = h;
    }
    if (pxmax < -1.0f || pymax < -1.0f || pxmin > w + 1.0f || pymin > h + 1.0f) return;
    int x0 = vx_f2i(vx_fmax(vx_floor(pxmin) - 1.0f, 0.0f)), x1 = vx_f2i(vx_fmin(vx_floor(pxmax) + 2.0f, w));
    int y0 = vx_f2i(vx_fmax(vx_floor(pymin) - 1.0f, 0.0f)), y1 = vx_f2i(vx_fmin(vx_floor(pymax) + 2.0f, h));
    uint slot = vx_atomic_add(f, VX_WF_HEADER_VISIBLE_COUNT, 1u);
    if (slot >= vx_frame_load(f, VX_WF_HEADER_VISIBLE_CAPACITY)) return;
    uint at = vx_frame_load(f, VX_WF_HEADER_VISIBLE_AT) + slot * VX_WF_VISIBLE_WORDS;
    vx_frame_store(f, at + 0u, i);
    vx_frame_store(f, at + 1u, vx_i2u(x0 >> VX_WF_TILE_BITS) | (vx_i2u(y0 >> VX_WF_TILE_BITS) << 16));
    vx_frame_store(f, at + 2u, vx_i2u(x1 >> VX_WF_TILE_BITS) | (vx_i2u(y1 >> VX_WF_TILE_BITS) << 16));
    /* One voxel nearer than the nearest corner: rounding never makes a hit nearer than this. */
    vx_frame_store(f, at + 3u, vx_wf_depth_key(zmin - 1.0f, v.depth_scale));
}

VX_FN uint vx_wf_visible_count(VX_FRAME f) {
    uint count = vx_frame_load(f, VX_WF_HEADER_VISIBLE_COUNT), capacity = vx_frame_load(f, VX_WF_HEADER_VISIBLE_CAPACITY);
    return count < capacity ? count : capacity;
}

/* Whether tile `tile` of visible chunk k (near key `near_key`) is marched in this selection:
 * against the previous frame's Hi-Z (again = false), or, having failed that test, against
 * this frame's. */
VX_FN bool vx_wf_tile_taken(VX_FRAME f, uint near_key, uint tile, uint hiz_previous, uint hiz_current, bool again) {
    bool passed = near_key >= vx_frame_load(f, hiz_previous + tile);
    return again ? (!passed && near_key >= vx_frame_load(f, hiz_current + tile)) : passed;
}

/* Item = (visible chunk k, tile row ty), k-major: the tiles of one row of k's rect that it
 * is marched in. A row counts its pairs first and claims their slots with one atomic add:
 * one item per chunk with an atomic per pair serialized millions of pairs on one counter
 * (50 ms of a 71 ms frame at 3840 x 2160 on an H200, docs/benchmarks.md). */
VX_FN void vx_wf_select_tiles(VX_FRAME f, uint item, bool again) {
    uint tiles_x = vx_frame_load(f, VX_WF_HEADER_TILES_X), tiles_y = vx_frame_load(f, VX_WF_HEADER_TILES_Y);
    uint k = item / tiles_y, ty = item - k * tiles_y;
    if (k >= vx_wf_visible_count(f)) return;
    uint at = vx_frame_load(f, VX_WF_HEADER_VISIBLE_AT) + k * VX_WF_VISIBLE_WORDS;
    uint lo = vx_frame_load(f, at + 1u), hi = vx_frame_load(f, at + 2u), near_key = vx_frame_load(f, at + 3u);
    if (ty < (lo >> 16) || ty > (hi >> 16)) return;
    uint tiles = tiles_x * tiles_y;
    uint previous = vx_frame_load(f, VX_WF_HEADER_HIZ_PREVIOUS);
    uint hiz_previous = vx_frame_load(f, VX_WF_HEADER_HIZ_AT) + previous * tiles;
    uint hiz_current = vx_frame_load(f, VX_WF_HEADER_HIZ_AT) + (1u - previous) * tiles;
    uint row = ty * tiles_x, x0 = lo & 65535u, x1 = hi & 65535u;
    uint taken = 0u;
    for (uint tx = x0; tx <= x1; ++tx)
        if (vx_wf_tile_taken(f, near_key, row + tx, hiz_previous, hiz_current, again)) ++taken;
    if (taken == 0u) return;
    uint slot = vx_atomic_add(f, VX_WF_HEADER_PAIR_COUNT, taken);
    uint pairs = vx_frame_load(f, VX_WF_HEADER_PAIRS_AT), capacity = vx_frame_load(f, VX_WF_HEADER_PAIR_CAPACITY);
    for (uint tx = x0; tx <= x1 && slot < capacity; ++tx) {
        if (!vx_wf_tile_taken(f, near_key, row + tx, hiz_previous, hiz_current, again)) continue;
        /* slot >= capacity: the host sees the count, grows the list, runs again */
        vx_frame_store(f, pairs + slot * VX_WF_PAIR_WORDS, row + tx);
        vx_frame_store(f, pairs + slot * VX_WF_PAIR_WORDS + 1u, k);
        ++slot;
    }
}

/* The ray's span [t0, t1] through box [lo, hi) on one axis, widened by 1/64 voxel. */
VX_STRUCT(vx_wf_span)
    float t0, t1;
VX_END_STRUCT(vx_wf_span)

VX_FN vx_wf_span vx_wf_slab(vx_wf_span s, float o, float d, float lo, float hi) {
    lo = lo - 0.015625f;
    hi = hi + 0.015625f;
    if (d == 0.0f) {
        if (o < lo || o > hi) s.t0 = VX_INF;
        return s;
    }
    float inv = 1.0f / d;
    float ta = (lo - o) * inv, tb = (hi - o) * inv;
    s.t0 = vx_fmax(s.t0, vx_fmin(ta, tb));
    s.t1 = vx_fmin(s.t1, vx_fmax(ta, tb));
    return s;
}

/* Pixel `item & 63` of pair `item >> 6`, through that pair's chunk only: the world's walk
 * restricted to the chunk's entry, ending a little past the chunk's box. */
VX_FN void vx_wf_march(VX_BLOB blob, VX_FRAME f, uint item) {
    uint pair = item >> 6;
    uint count = vx_frame_load(f, VX_WF_HEADER_PAIR_COUNT), capacity = vx_frame_load(f, VX_WF_HEADER_PAIR_CAPACITY);
    if (pair >= (count < capacity ? count : capacity)) return;
    vx_wf_view v = vx_wf_load_view(f);
    uint pairs = vx_frame_load(f, VX_WF_HEADER_PAIRS_AT);
    uint tile = vx_frame_load(f, pairs + pair * VX_WF_PAIR_WORDS), k = vx_frame_load(f, pairs + pair * VX_WF_PAIR_WORDS + 1u);
    int px = vx_u2i(((tile % vx_i2u(v.tiles_x)) << VX_WF_TILE_BITS) + (item & 7u));
    int py = vx_u2i(((tile / vx_i2u(v.tiles_x)) << VX_WF_TILE_BITS) + ((item >> 3) & 7u));
    if (px >= v.width || py >= v.height) return;
    vx_ray r = vx_wf_pixel_ray(v, px, py);
    uint row = vx_wf_row(blob, vx_frame_load(f, vx_frame_load(f, VX_WF_HEADER_VISIBLE_AT) + k * VX_WF_VISIBLE_WORDS));
    vx_wf_span s;
    s.t0 = 0.0f;
    s.t1 = VX_INF;
    s = vx_wf_slab(s, r.ox, r.dx, vx_wf_box(blob, row, VX_WD_ROW_MIN, 0u), vx_wf_box(blob, row, VX_WD_ROW_MAX, 0u));
    s = vx_wf_slab(s, r.oy, r.dy, vx_wf_box(blob, row, VX_WD_ROW_MIN, 1u), vx_wf_box(blob, row, VX_WD_ROW_MAX, 1u));
    s = vx_wf_slab(s, r.oz, r.dz, vx_wf_box(blob, row, VX_WD_ROW_MIN, 2u), vx_wf_box(blob, row, VX_WD_ROW_MAX, 2u));
    if (!(s.t0 <= s.t1)) return;
    /* A hit already in that is strictly nearer than the box cannot be beaten by this chunk
     * (its hits are no nearer than its box): skip the walk. Strictly, so a tie still goes
     * to the atomic max and the buffer is the same whatever order the pairs run in. The
     * host orders visible chunks nearest first (world/frame/frame.hpp), so most pixels behind a
     * near surface skip the chunks behind it. */
    uint at = vx_frame_load(f, VX_WF_HEADER_VISIBILITY_AT) + 2u * vx_i2u(py * v.width + px);
    if (VX_WF_DEPTH(vx_frame_load(f, at + 1u)) > vx_wf_depth_key(s.t0, v.depth_scale)) return;
    /* The walk finds nothing of this chunk outside its box: start two voxels before it
     * (|d| >= 1, and the walk restricted to this chunk sees only empty space there, so it
     * enters the box as a walk from the camera would: the DDA's crossings are computed from
     * the origin, not accumulated), and stop past it (with a margin for the slab's rounding;
     * a later stop only costs steps). Skipping the directory walk from the camera to the
     * chunk is most of the march's saving over tracing the whole world per pair. */
    r.tmin = vx_fmax(s.t0 - 2.0f, 0.0f);
    r.tmax = s.t1 * 1.0001f + 0.01f;
    vx_world g = vx_world_load(blob);
    vx_wd_state st = vx_world_begin(g, r);
    st.only = vx_load(blob, row + VX_WD_ROW_ENTRY);
    while (st.walk.w.status == VX_STATUS_ACTIVE) st = vx_world_step(blob, g, st);
    if (st.walk.w.status != VX_STATUS_HIT) return;
    uint key = vx_wf_depth_key(st.walk.w.t, v.depth_scale);
    if (key == 0u) return;
    uint lod = st.walk.lod, last = (1u << vx_i2u(g.chunk_bits)) - 1u;
    uint x = (vx_i2u(st.walk.w.cx + g.f.shx) >> lod) & last;
    uint y = (vx_i2u(st.walk.w.cy + g.f.shy) >> lod) & last;
    uint z = (vx_i2u(st.walk.w.cz + g.f.shz) >> lod) & last;
    vx_atomic_max64(f, at, VX_WF_PACK_HI(key, st.walk.w.face, k), VX_WF_PACK_LO(k, x, y, z));
}

/* This frame's Hi-Z for `tile`: the smallest depth key of its pixels (0 where one has no hit). */
VX_FN void vx_wf_build_hiz(VX_FRAME f, uint tile) {
    uint width = vx_frame_load(f, VX_WF_HEADER_WIDTH), height = vx_frame_load(f, VX_WF_HEADER_HEIGHT);
    uint tiles_x = vx_frame_load(f, VX_WF_HEADER_TILES_X);
    uint tiles = tiles_x * vx_frame_load(f, VX_WF_HEADER_TILES_Y);
    if (tile >= tiles) return;
    uint visibility = vx_frame_load(f, VX_WF_HEADER_VISIBILITY_AT);
    uint farthest = VX_WF_DEPTH_MAX;
    for (uint p = 0u; p < VX_WF_TILE_PIXELS; ++p) {
        uint px = ((tile % tiles_x) << VX_WF_TILE_BITS) + (p & 7u), py = ((tile / tiles_x) << VX_WF_TILE_BITS) + (p >> 3);
        if (px >= width || py >= height) continue;
        uint key = VX_WF_DEPTH(vx_frame_load(f, visibility + 2u * (py * width + px) + 1u));
        farthest = key < farthest ? key : farthest;
    }
    uint previous = vx_frame_load(f, VX_WF_HEADER_HIZ_PREVIOUS);
    vx_frame_store(f, vx_frame_load(f, VX_WF_HEADER_HIZ_AT) + (1u - previous) * tiles + tile, farthest);
}

/* The hit's attribute from its visibility word: the voxel's depth-first index in its
 * chunk's DAG, then the colour block (or exact payload) holding it, as a trace's hit. */
VX_FN void vx_wf_resolve(VX_BLOB blob, VX_FRAME f, uint pixel) {
    uint pixels = vx_frame_load(f, VX_WF_HEADER_WIDTH) * vx_frame_load(f, VX_WF_HEADER_HEIGHT);
    if (pixel >= pixels) return;
    uint at = vx_frame_load(f, VX_WF_HEADER_VISIBILITY_AT) + 2u * pixel;
    uint lo = vx_frame_load(f, at), hi = vx_frame_load(f, at + 1u);
    uint material = 0u;
    if ((lo | hi) != 0u) {
        uint k = VX_WF_CHUNK(hi, lo);
        uint row = vx_wf_row(blob, vx_frame_load(f, vx_frame_load(f, VX_WF_HEADER_VISIBLE_AT) + k * VX_WF_VISIBLE_WORDS));
        uint entry = vx_load(blob, row + VX_WD_ROW_ENTRY) - VX_WD_CHILD_IS_ENTRY;
        uint dag = vx_load(blob, entry + VX_WD_ENTRY_DAG);
        int depth = vx_u2i(vx_load(blob, VX_WD_HEADER_CHUNK_BITS));
        uint index = vx_sv_dfs_index(blob, depth, dag, VX_WF_X(lo), VX_WF_Y(lo), VX_WF_Z(lo), true);
        material = vx_sv_attribute(blob, vx_load(blob, VX_WD_HEADER_ATTRIBUTE_KIND), dag, index, true);
    }
    vx_frame_store(f, vx_frame_load(f, VX_WF_HEADER_MATERIAL_AT) + pixel, material);
}

/* One item of pass `pass` (VX_WF_PASS_*): the single entry point every backend calls. */
VX_FN void vx_world_pass(VX_BLOB blob, VX_FRAME f, uint pass, uint item) {
    if (pass == VX_WF_PASS_CLEAR) vx_wf_clear(f, item);
    else if (pass == VX_WF_PASS_SELECT_CHUNKS) vx_wf_select_chunk(blob, f, item);
    else if (pass == VX_WF_PASS_SELECT_TILES) vx_wf_select_tiles(f, item, false);
    else if (pass == VX_WF_PASS_SELECT_TILES_AGAIN) vx_wf_select_tiles(f, item, true);
    else if (pass == VX_WF_PASS_MARCH) vx_wf_march(blob, f, item);
    else if (pass == VX_WF_PASS_BUILD_HIZ) vx_wf_build_hiz(f, item);
    else if (pass == VX_WF_PASS_RESOLVE) vx_wf_resolve(blob, f, item);
}
