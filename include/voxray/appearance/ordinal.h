/* The ordinal index's lookup (layout in appearance/ordinal_layout.h): a voxel's row in an
 * appearance table, for any structure. Needs prelude.h and kernels/bits.h. Included once per
 * lane set; no include guard on purpose. */
#include "voxray/appearance/ordinal_layout.h"

/* The row of voxel (x, y, z) (world voxel units), or VX_APP_NO_ROW when it has none. */
VX_FN uint vx_app_row(VX_BLOB index, int x, int y, int z) {
    int rx = x - vx_u2i(vx_load(index, 0u)), ry = y - vx_u2i(vx_load(index, 1u)), rz = z - vx_u2i(vx_load(index, 2u));
    int bx = vx_u2i(vx_load(index, 3u)), by = vx_u2i(vx_load(index, 4u)), bz = vx_u2i(vx_load(index, 5u));
    if (rx < 0 || ry < 0 || rz < 0 || (rx >> 2) >= bx || (ry >> 2) >= by || (rz >> 2) >= bz) return VX_APP_NO_ROW;
    uint brick = vx_load(index, VX_APP_ORD_HEADER_WORDS + vx_i2u(((rz >> 2) * by + (ry >> 2)) * bx + (rx >> 2)));
    if (brick == VX_APP_NO_BRICK) return VX_APP_NO_ROW;
    uint at = vx_load(index, 6u) + brick * VX_APP_ORD_RECORD_WORDS;
    uint bit = vx_i2u(VX_APP_BRICK_BIT(rx, ry, rz)), lo = vx_load(index, at + 1u), hi = vx_load(index, at + 2u);
    uint word = bit < 32u ? lo : hi, below = word & ((1u << (bit & 31u)) - 1u);
    if (((word >> (bit & 31u)) & 1u) == 0u) return VX_APP_NO_ROW;
    return vx_load(index, at) + (bit < 32u ? 0u : vx_popcount(lo)) + vx_popcount(below);
}
