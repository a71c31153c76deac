/* Bit counting in the portable dialect, the same arithmetic on every lane set (no
 * intrinsic, so scalar C++, SIMD lanes, OpenCL C and GLSL agree by construction).
 *
 *   vx_popcount(x)     the number of set bits of a 32-bit word
 *   vx_bit_length(x)   the position of the highest set bit plus one (0 for x = 0),
 *                      exact for x < 2^24 (through a float's exponent; larger x may
 *                      come out one too high)
 *
 * Included once per lane set; no include guard on purpose (see cpu/lanes.hpp). */

VX_FN vx_u32 vx_popcount(vx_u32 x) {
    x = x - ((x >> 1) & 0x55555555u);
    x = (x & 0x33333333u) + ((x >> 2) & 0x33333333u);
    x = (x + (x >> 4)) & 0x0F0F0F0Fu;
    return (x * 0x01010101u) >> 24;
}

/* float(x) (as a signed int: cheaper on SIMD lanes) is exact below 2^24, and its biased exponent is then 127 + floor(log2 x). */
VX_FN vx_i32 vx_bit_length(vx_u32 x) {
    vx_i32 exponent = vx_u2i(vx_f_bits(vx_i2f(vx_u2i(x))) >> 23) - 126;
    return vx_sel(x == 0u, 0, exponent);
}
