// Seeded hashing and value noise for the procedural scenes. Our own small
// functions, not <random> distributions: those differ between standard library
// versions, and a scene must be the same voxels everywhere. Only integer ops,
// +, * and floor are used, so results are bit-identical on any IEEE machine.
#pragma once
#include <cmath>
#include <cstdint>

namespace voxray::scenes {

// splitmix64's finalizer: a strong 64-bit mix.
inline std::uint64_t mix64(std::uint64_t z) {
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// Hash of a seed, a purpose tag and up to three integers.
inline std::uint64_t hash(std::uint64_t seed, std::uint64_t tag, std::int64_t a, std::int64_t b = 0, std::int64_t c = 0) {
    std::uint64_t h = mix64(seed ^ (tag * 0x9E3779B97F4A7C15ull));
    h = mix64(h ^ std::uint64_t(a));
    h = mix64(h ^ (std::uint64_t(b) * 0xC2B2AE3D27D4EB4Full));
    return mix64(h ^ (std::uint64_t(c) * 0x165667B19E3779F9ull));
}

// Uniform in [0, 1) from the top 53 bits.
inline double unit(std::uint64_t h) { return double(h >> 11) * 0x1.0p-53; }

// A small sequential generator for placing things (splitmix64).
struct rng {
    std::uint64_t state;
    std::uint64_t next() { return mix64(state += 0x9E3779B97F4A7C15ull); }
    double uniform() { return unit(next()); }
    int range(int lo, int hi) { return lo + int(next() % std::uint64_t(hi - lo + 1)); }  // inclusive
};

// 2-D value noise in [0, 1): random values on an integer lattice, blended with
// a quintic fade (smooth first and second derivatives, so no creases).
inline double value_noise(std::uint64_t seed, std::uint64_t tag, double x, double y) {
    double fx = std::floor(x), fy = std::floor(y);
    auto ix = std::int64_t(fx), iy = std::int64_t(fy);
    double tx = x - fx, ty = y - fy;
    auto fade = [](double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); };
    double u = fade(tx), v = fade(ty);
    double a = unit(hash(seed, tag, ix, iy)), b = unit(hash(seed, tag, ix + 1, iy));
    double c = unit(hash(seed, tag, ix, iy + 1)), d = unit(hash(seed, tag, ix + 1, iy + 1));
    double top = a + (b - a) * u, bottom = c + (d - c) * u;
    return top + (bottom - top) * v;
}

// Fractal sum of `octaves` value noises, each twice the frequency and half the
// amplitude of the last; normalised to [0, 1).
inline double fbm(std::uint64_t seed, std::uint64_t tag, double x, double y, int octaves) {
    double sum = 0, amp = 1, norm = 0, freq = 1;
    for (int o = 0; o < octaves; ++o) {
        sum += amp * value_noise(seed, tag + std::uint64_t(o), x * freq, y * freq);
        norm += amp;
        amp *= 0.5;
        freq *= 2.0;
    }
    return sum / norm;
}

}  // namespace voxray::scenes
