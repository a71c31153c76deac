// The sampling rays of one voxel (the paper's section 3.2): directions over the sphere, and
// for each an entry point uniform over the voxel's projection along it, so every part of
// what the voxel shows from that direction is equally likely to be sampled. A ray runs
// from its entry point to where it leaves the voxel.
//
// Entry points: the faces the ray enters through are the (up to) three whose outward normal
// opposes it; face a is picked with probability |d_a| / (|d_x| + |d_y| + |d_z|), its
// projected share, then a point uniform on it. Directions: a spherical Fibonacci set,
// turned by a random angle per voxel (stratified, the default), or independent uniform ones.
// Random numbers come from a counter-based generator keyed by (seed, voxel, ray), so a
// voxel's rays do not depend on which thread samples it, or when.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>

#include <glm/vec3.hpp>

namespace voxray::appearance {

// SplitMix64's finalizer: a well-mixed 64-bit value from any counter.
inline std::uint64_t mix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// A uniform double in [0, 1) from draw `k` of the stream keyed by (seed, voxel, ray).
inline double uniform01(std::uint64_t seed, glm::ivec3 voxel, std::uint32_t ray, std::uint32_t k) {
    std::uint64_t key = mix64(seed ^ mix64(std::uint64_t(std::uint32_t(voxel.x)) |
                                           std::uint64_t(std::uint32_t(voxel.y)) << 32));
    key = mix64(key ^ std::uint64_t(std::uint32_t(voxel.z)) ^ (std::uint64_t(ray) << 32 | k));
    return double(key >> 11) * 0x1.0p-53;
}

struct sampling_ray {
    glm::dvec3 origin{0.0};     // on the voxel's surface
    glm::dvec3 direction{0.0};  // unit length
    double length = 0;          // to where it leaves the voxel
};

// How far a ray from point p of the unit cube along unit d goes before it leaves the cube:
// to the nearest exit plane along each moving axis.
inline double exit_length(glm::dvec3 p, glm::dvec3 d) {
    double length = 1e30;
    for (int a = 0; a < 3; ++a)
        if (d[a] != 0.0) length = std::min(length, ((d[a] > 0 ? 1.0 : 0.0) - p[a]) / d[a]);
    return std::max(length, 0.0);
}

// Ray `i` of `count` through voxel `voxel` (the unit cube at its integer corner).
inline sampling_ray voxel_ray(glm::ivec3 voxel, std::uint32_t i, std::uint32_t count, bool stratified,
                              std::uint64_t seed) {
    constexpr double pi = std::numbers::pi;
    double z, phi;
    if (stratified) {  // spherical Fibonacci, turned per voxel
        z = 1.0 - (2.0 * double(i) + 1.0) / double(count);
        phi = 2.0 * pi * (double(i) * 0.6180339887498949 + uniform01(seed, voxel, 0xFFFFFFFFu, 0));
    } else {
        z = 1.0 - 2.0 * uniform01(seed, voxel, i, 0);
        phi = 2.0 * pi * uniform01(seed, voxel, i, 1);
    }
    double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    glm::dvec3 d(r * std::cos(phi), r * std::sin(phi), z);
    // The entry face, by projected area, then a point on it.
    double weights[3] = {std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)};
    double pick = uniform01(seed, voxel, i, 2) * (weights[0] + weights[1] + weights[2]);
    int axis = pick < weights[0] ? 0 : (pick < weights[0] + weights[1] ? 1 : 2);
    glm::dvec3 p(uniform01(seed, voxel, i, 3), uniform01(seed, voxel, i, 4), uniform01(seed, voxel, i, 5));
    p[axis] = d[axis] > 0 ? 0.0 : 1.0;
    return {glm::dvec3(voxel) + p, d, exit_length(p, d)};
}

}  // namespace voxray::appearance
