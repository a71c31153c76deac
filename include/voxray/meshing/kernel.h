/* The mesher as a kernel in the portable dialect: the same quads, in the same POP order,
 * as the CPU mesher (meshing/mesher.hpp), bit for bit, on OpenCL, Vulkan and the CPU's
 * scalar lanes. Buffers: meshing/kernel_layout.h. Host: meshing/kernel_words.hpp and each
 * backend's chunk_mesher.
 *
 * The greedy merge of one face direction works plane by plane (a layer along the normal),
 * and no plane reads another, so a plane is the unit of work: 384 items a chunk (6 faces
 * x 64 layers), each walking its plane exactly as the CPU mesher does (rows in order, the
 * border ring first as unit quads, then runs from the lowest bit, grown down the rows).
 * The CPU's order within a level bucket is plane by plane, so three passes give the same
 * buffer without any item waiting for another:
 *   count   each plane counts its quads per level;
 *   place   one item a chunk turns the counts into starts, face-major and coarse to fine
 *           (layout.h), and writes the table;
 *   emit    each plane walks again and writes its quads at its starts.
 * Walking twice costs one more merge per plane, and needs no work-group memory, no barrier
 * and no atomic: every backend, the CPU's scalar lanes included, runs the same items.
 *
 * Included once (scalar lanes); no include guard. */
#include "voxray/meshing/kernel_layout.h"

/* Is voxel (x, y, z) of the padded chunk solid? x, y, z in -1..64. */
VX_FN bool vx_mk_solid(VX_BLOB blob, uint base, int x, int y, int z) {
    uint row = vx_i2u(VX_MK_ROW(y, z));
    if (x < 0 || x > 63) {
        uint shell = base + (x < 0 ? VX_MK_X_LOW : VX_MK_X_HIGH);
        return ((vx_load(blob, shell + (row >> 5)) >> (row & 31u)) & 1u) != 0u;
    }
    uint word = vx_load(blob, base + VX_MK_ROWS + 2u * row + vx_i2u(x >> 5));
    return ((word >> vx_i2u(x & 31)) & 1u) != 0u;
}

VX_FN uint vx_mk_material(VX_BLOB blob, uint base, int x, int y, int z) {
    uint i = vx_i2u(x + 64 * (y + 64 * z));
    return (vx_load(blob, base + VX_MK_MATERIALS + (i >> 2)) >> ((i & 3u) * 8u)) & 0xFFu;
}

/* Coordinate `axis` of the voxel at (layer, row r, bit b) of a plane of normal axis
 * `normal` (mesher.hpp's voxel()): the layer along the normal, the bit along the lower of
 * the other two axes, the row along the higher. */
VX_FN int vx_mk_coord(uint normal, uint axis, int layer, int r, int b) {
    if (axis == normal) return layer;
    return axis == (normal == 0u ? 1u : 0u) ? b : r;
}

/* Ambient occlusion of a unit face (meshing/face_ao.hpp's rule and corner order). */
VX_FN uint vx_mk_ao(VX_BLOB blob, uint base, int x, int y, int z, uint face) {
    uint n = VX_MESH_NORMAL_AXIS(face), u = VX_MESH_U_AXIS(face), v = VX_MESH_V_AXIS(face);
    int toward = VX_MESH_POSITIVE(face) ? 1 : -1;
    int fx = x + (n == 0u ? toward : 0), fy = y + (n == 1u ? toward : 0), fz = z + (n == 2u ? toward : 0);
    uint bits = 0u;
    for (uint corner = 0u; corner < 4u; ++corner) {
        int du = (corner == 1u || corner == 2u) ? 1 : -1, dv = corner >= 2u ? 1 : -1;
        int ux = u == 0u ? du : 0, uy = u == 1u ? du : 0, uz = u == 2u ? du : 0;
        int vx = v == 0u ? dv : 0, vy = v == 1u ? dv : 0, vz = v == 2u ? dv : 0;
        uint side_u = vx_mk_solid(blob, base, fx + ux, fy + uy, fz + uz) ? 1u : 0u;
        uint side_v = vx_mk_solid(blob, base, fx + vx, fy + vy, fz + vz) ? 1u : 0u;
        uint diagonal = vx_mk_solid(blob, base, fx + ux + vx, fy + uy + vy, fz + uz + vz) ? 1u : 0u;
        uint corner_ao = (side_u == 1u && side_v == 1u) ? 0u : 3u - (side_u + side_v + diagonal);
        bits |= corner_ao << (2u * corner);
    }
    return bits;
}

/* What a face must share with its neighbours to merge: material, and AO when it is on. */
VX_FN uint vx_mk_key(VX_BLOB blob, uint base, uint face, int layer, int r, int b, bool ao) {
    uint normal = VX_MESH_NORMAL_AXIS(face);
    int x = vx_mk_coord(normal, 0u, layer, r, b), y = vx_mk_coord(normal, 1u, layer, r, b);
    int z = vx_mk_coord(normal, 2u, layer, r, b);
    uint key = vx_mk_material(blob, base, x, y, z);
    if (ao) key |= vx_mk_ao(blob, base, x, y, z, face) << 16;
    return key;
}

/* Row r of the plane: bit b set where the face at (layer, r, b) is visible. As two words
 * (bits 0..31, 32..63), since GLSL has no 64-bit integer without a device feature. */
VX_FN uint vx_mk_plane_word(VX_BLOB blob, uint base, uint face, int layer, int r, uint part) {
    uint normal = VX_MESH_NORMAL_AXIS(face);
    int toward = VX_MESH_POSITIVE(face) ? 1 : -1;
    uint rows = base + VX_MK_ROWS + part;
    if (normal == 2u)
        return vx_load(blob, rows + 2u * vx_i2u(VX_MK_ROW(r, layer))) &
               ~vx_load(blob, rows + 2u * vx_i2u(VX_MK_ROW(r, layer + toward)));
    if (normal == 1u)
        return vx_load(blob, rows + 2u * vx_i2u(VX_MK_ROW(layer, r))) &
               ~vx_load(blob, rows + 2u * vx_i2u(VX_MK_ROW(layer + toward, r)));
    /* X faces: bits along y, one voxel pair per bit. */
    uint word = 0u;
    for (int bit = 0; bit < 32; ++bit) {
        int y = vx_u2i(part) * 32 + bit;
        bool here = vx_mk_solid(blob, base, layer, y, r), beyond = vx_mk_solid(blob, base, layer + toward, y, r);
        if (here && !beyond) word |= 1u << vx_i2u(bit);
    }
    return word;
}

/* Bits [from, to) of a 64-bit row, as its word `part` (0: bits 0..31, 1: 32..63). */
VX_FN uint vx_mk_span(int from, int to, uint part) {
    int lo = from - vx_u2i(part) * 32, hi = to - vx_u2i(part) * 32;
    lo = lo < 0 ? 0 : (lo > 32 ? 32 : lo);
    hi = hi < 0 ? 0 : (hi > 32 ? 32 : hi);
    uint below_hi = hi >= 32 ? 0xFFFFFFFFu : ((1u << vx_i2u(hi)) - 1u);
    uint below_lo = lo >= 32 ? 0xFFFFFFFFu : ((1u << vx_i2u(lo)) - 1u);
    return below_hi & ~below_lo;
}

VX_FN bool vx_mk_bit(uint low, uint high, int b) {
    return (((b < 32 ? low : high) >> vx_i2u(b & 31)) & 1u) != 0u;
}

/* The POP level of a quad over [u0, u0 + w) x [v0, v0 + h) (layout.h; mesher.hpp's quad_level). */
VX_FN uint vx_mk_level(int u0, int w, int v0, int h) {
    vx_i32 along_u = vx_bit_length(vx_i2u(u0 ^ (u0 + w))), along_v = vx_bit_length(vx_i2u(v0 ^ (v0 + h)));
    vx_i32 level = along_u < along_v ? along_u : along_v;
    return vx_i2u(level < VX_MESH_MAX_LEVEL ? level : VX_MESH_MAX_LEVEL);
}

/* One quad of a plane: counted (pass count) or written at its level's cursor (pass emit). */
VX_FN void vx_mk_quad(VX_FRAME frame, uint block, uint counters, uint face, int layer, int r, int b, int run,
                      int rows, uint key, uint flags, bool write) {
    uint normal = VX_MESH_NORMAL_AXIS(face);
    int x = vx_mk_coord(normal, 0u, layer, r, b), y = vx_mk_coord(normal, 1u, layer, r, b);
    int z = vx_mk_coord(normal, 2u, layer, r, b);
    bool bits_along_u = normal != 1u;
    int w = bits_along_u ? run : rows, h = bits_along_u ? rows : run;
    uint level = VX_MESH_MAX_LEVEL;
    if ((flags & VX_MK_FLAG_POP) != 0u)
        level = vx_mk_level(vx_mk_coord(normal, VX_MESH_U_AXIS(face), layer, r, b), w,
                            vx_mk_coord(normal, VX_MESH_V_AXIS(face), layer, r, b), h);
    uint at = vx_frame_load(frame, counters + level);
    vx_frame_store(frame, counters + level, at + 1u);
    if (!write) return;
    uint ao = (flags & VX_MK_FLAG_AO) != 0u ? (key >> 16) : VX_MESH_AO_OPEN;
    uint quad = block + VX_MK_QUADS + at * VX_MESH_QUAD_WORDS;
    vx_frame_store(frame, quad, VX_MESH_WORD0(vx_i2u(x), vx_i2u(y), vx_i2u(z), vx_i2u(w), vx_i2u(h)));
    vx_frame_store(frame, quad + 1u, VX_MESH_WORD1(key & 0xFFFFu, ao, face, level));
}

/* Walks plane `item` of its chunk (mesher.hpp's merge_planes, one layer): counts its
 * quads, or writes them. */
VX_FN void vx_mk_plane(VX_BLOB blob, VX_FRAME frame, uint item, bool write) {
    uint flags = vx_frame_load(frame, VX_MK_HEADER_FLAGS);
    uint capacity = vx_frame_load(frame, VX_MK_HEADER_CAPACITY);
    uint chunk = item / VX_MK_PLANES, plane = item % VX_MK_PLANES;
    uint face = plane / 64u;
    int layer = vx_u2i(plane % 64u);
    uint base = chunk * VX_MK_CHUNK_WORDS;
    uint block = VX_MK_HEADER_WORDS + chunk * VX_MK_BLOCK_WORDS(capacity);
    uint counters = block + plane * VX_MK_COUNTERS;
    if (write && vx_frame_load(frame, block + VX_MK_TOTAL) > capacity) return;
    if (!write)
        for (uint level = 0u; level < VX_MK_COUNTERS; ++level) vx_frame_store(frame, counters + level, 0u);
    bool ao = (flags & VX_MK_FLAG_AO) != 0u;
    uint low[64];
    uint high[64];
    for (int r = 0; r < 64; ++r) {
        low[r] = vx_mk_plane_word(blob, base, face, layer, r, 0u);
        high[r] = vx_mk_plane_word(blob, base, face, layer, r, 1u);
    }
    for (int r = 0; r < 64; ++r) {
        /* The border ring: faces with a corner on a chunk side stay unit quads (all of
         * rows 0 and 63, bits 0 and 63 of the others), in bit order. */
        bool edge_row = r == 0 || r == 63;
        for (int b = 0; b < 64; ++b)
            if ((edge_row || b == 0 || b == 63) && vx_mk_bit(low[r], high[r], b))
                vx_mk_quad(frame, block, counters, face, layer, r, b, 1, 1,
                           vx_mk_key(blob, base, face, layer, r, b, ao), flags, write);
        if (edge_row) continue;
        /* Runs from the lowest bit: as long as the faces share the first one's key, then
         * grown down the rows while the next row holds the same run with the same key. */
        for (int b = 1; b < 63; ++b) {
            if (!vx_mk_bit(low[r], high[r], b)) continue;
            uint key = vx_mk_key(blob, base, face, layer, r, b, ao);
            int end = b + 1;
            while (end < 63 && vx_mk_bit(low[r], high[r], end) && vx_mk_key(blob, base, face, layer, r, end, ao) == key)
                ++end;
            uint span_low = vx_mk_span(b, end, 0u), span_high = vx_mk_span(b, end, 1u);
            low[r] &= ~span_low;
            high[r] &= ~span_high;
            int r2 = r + 1;
            for (; r2 < 63; ++r2) {
                bool same = (low[r2] & span_low) == span_low && (high[r2] & span_high) == span_high;
                for (int s = b; same && s < end; ++s) same = vx_mk_key(blob, base, face, layer, r2, s, ao) == key;
                if (!same) break;
                low[r2] &= ~span_low;
                high[r2] &= ~span_high;
            }
            vx_mk_quad(frame, block, counters, face, layer, r, b, end - b, r2 - r, key, flags, write);
            b = end - 1;
        }
    }
}

/* One chunk's counts -> starts, face-major, coarse to fine, plane by plane; the table. */
VX_FN void vx_mk_place(VX_FRAME frame, uint chunk) {
    uint capacity = vx_frame_load(frame, VX_MK_HEADER_CAPACITY);
    uint block = VX_MK_HEADER_WORDS + chunk * VX_MK_BLOCK_WORDS(capacity);
    uint at = 0u;
    for (uint face = 0u; face < VX_MESH_FACES; ++face)
        for (uint level = VX_MESH_MAX_LEVEL; level >= 1u; --level) {
            for (uint layer = 0u; layer < 64u; ++layer) {
                uint counter = block + (face * 64u + layer) * VX_MK_COUNTERS + level;
                uint n = vx_frame_load(frame, counter);
                vx_frame_store(frame, counter, at);
                at += n;
            }
            vx_frame_store(frame, block + VX_MK_TABLE + VX_MESH_TABLE_END(face, level - 1u), at);
        }
    vx_frame_store(frame, block + VX_MK_TOTAL, at);
}

VX_FN void vx_mesher_pass(VX_BLOB blob, VX_FRAME frame, uint pass, uint item) {
    if (pass == VX_MK_PASS_PLACE) vx_mk_place(frame, item);
    else vx_mk_plane(blob, frame, item, pass == VX_MK_PASS_EMIT);
}
