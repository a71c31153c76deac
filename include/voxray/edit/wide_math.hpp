// Exact integer arithmetic wider than 64 bits for the edit regions: coordinates span
// 2^32, so squared distances need 66 bits and the capsule's scaled comparison ~134.
// __extension__ keeps -Wpedantic quiet about the (GCC and Clang) 128-bit type.
#pragma once
#include <cstdint>

namespace voxray::regions {

__extension__ typedef __int128 i128;
__extension__ typedef unsigned __int128 u128;

// A 256-bit unsigned value, hi:lo, enough for the product of two values below 2^128.
struct u256 {
    u128 hi = 0, lo = 0;
    friend bool operator<=(const u256& a, const u256& b) { return a.hi != b.hi ? a.hi < b.hi : a.lo <= b.lo; }
    friend u256 operator+(const u256& a, const u256& b) {
        u256 s{a.hi + b.hi, a.lo + b.lo};
        if (s.lo < a.lo) ++s.hi;  // carry
        return s;
    }
};

inline u256 mul_wide(u128 a, u128 b) {
    const u128 mask = ~std::uint64_t(0);
    u128 a0 = a & mask, a1 = a >> 64, b0 = b & mask, b1 = b >> 64;
    u128 p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    // middle = p01 + p10 + (p00 >> 64) may carry past 128 bits: track it.
    u128 middle = p01 + (p00 >> 64);
    u128 carry = middle < p01 ? 1 : 0;
    u128 m2 = middle + p10;
    carry += m2 < middle ? 1 : 0;
    u256 r;
    r.lo = (m2 << 64) | (p00 & mask);
    r.hi = p11 + (m2 >> 64) + (carry << 64);
    return r;
}

inline u128 abs_wide(i128 v) { return v < 0 ? u128(-v) : u128(v); }

}  // namespace voxray::regions
