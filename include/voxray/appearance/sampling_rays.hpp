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
#include <map>
#include <numbers>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace voxray::appearance {

// SplitMix64's finalizer: a well-mixed 64-bit value from any counter.
inline std::uint64_t mix64(std::uint64_t x) {
    x += 0x9e3779b97f4a7c15ull;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
    return x ^ (x >> 31);
}

// The random stream of one voxel: a uniform double in [0, 1) for each (ray, draw) pair,
// keyed by (seed, voxel). The voxel's key is mixed once, its draws then cost one mix each.
class voxel_stream {
public:
    voxel_stream(std::uint64_t seed, glm::ivec3 voxel)
        : key_(mix64(seed ^ mix64(std::uint64_t(std::uint32_t(voxel.x)) |
                                  std::uint64_t(std::uint32_t(voxel.y)) << 32)) ^
               std::uint64_t(std::uint32_t(voxel.z))) {}
    double uniform01(std::uint32_t ray, std::uint32_t k) const {
        return double(mix64(key_ ^ (std::uint64_t(ray) << 32 | k)) >> 11) * 0x1.0p-53;
    }

private:
    std::uint64_t key_;
};

// Draw `k` of the stream keyed by (seed, voxel, ray), for one-off draws.
inline double uniform01(std::uint64_t seed, glm::ivec3 voxel, std::uint32_t ray, std::uint32_t k) {
    return voxel_stream(seed, voxel).uniform01(ray, k);
}

struct sampling_ray {
    glm::dvec3 origin{0.0};     // on the voxel's surface
    glm::dvec3 direction{0.0};  // unit length
    double length = 0;          // to where it leaves the voxel
};

// How far a ray from point p of the unit cube along unit d goes before it leaves the cube:
// to the nearest exit plane along each moving axis. The three divisions are one vector
// division (each lane rounded as a scalar one): they were the ray generator's longest wait.
inline double exit_length(glm::dvec3 p, glm::dvec3 d) {
    typedef double doubles __attribute__((vector_size(4 * sizeof(double))));
    const doubles far = {d.x > 0 ? 1.0 : 0.0, d.y > 0 ? 1.0 : 0.0, d.z > 0 ? 1.0 : 0.0, 0.0};
    const doubles along = (far - doubles{p.x, p.y, p.z, 0.0}) / doubles{d.x, d.y, d.z, 1.0};
    double length = 1e30;
    for (int a = 0; a < 3; ++a)
        if (d[a] != 0.0) length = std::min(length, along[a]);
    return std::max(length, 0.0);
}

// The `count` sampling rays of one voxel (the unit cube at its integer corner).
class voxel_rays {
public:
    voxel_rays(glm::ivec3 voxel, std::uint32_t count, bool stratified, std::uint64_t seed)
        : voxel_(voxel), stratified_(stratified), stream_(seed, voxel) {
        if (!stratified) return;
        // The Fibonacci set turned by one angle a voxel: each ray's own height, ring radius
        // and angle (the same for every voxel, made once a thread) turned by the voxel's.
        const double turn = 2.0 * std::numbers::pi * stream_.uniform01(0xFFFFFFFFu, 0);
        cos_turn_ = std::cos(turn), sin_turn_ = std::sin(turn);
        thread_local std::map<std::uint32_t, std::vector<fibonacci_node>> nodes_by_count;  // nodes stay put
        std::vector<fibonacci_node>& nodes = nodes_by_count[count];
        for (std::uint32_t i = std::uint32_t(nodes.size()); i < count; ++i) {
            double a = 2.0 * std::numbers::pi * (double(i) * 0.6180339887498949);
            double z = 1.0 - (2.0 * double(i) + 1.0) / double(count);
            nodes.push_back({std::cos(a), std::sin(a), z, ring_radius(z)});
        }
        nodes_ = nodes.data();
    }

    // Ray `i`: its direction, then its entry point.
    sampling_ray operator()(std::uint32_t i) const {
        double z, r, cos_phi, sin_phi;
        if (stratified_) {  // spherical Fibonacci, turned
            const fibonacci_node& n = nodes_[i];
            z = n.z, r = n.r;
            cos_phi = n.cos_a * cos_turn_ - n.sin_a * sin_turn_;
            sin_phi = n.sin_a * cos_turn_ + n.cos_a * sin_turn_;
        } else {
            z = 1.0 - 2.0 * stream_.uniform01(i, 0);
            r = ring_radius(z);
            double phi = 2.0 * std::numbers::pi * stream_.uniform01(i, 1);
            cos_phi = std::cos(phi), sin_phi = std::sin(phi);
        }
        glm::dvec3 d(r * cos_phi, r * sin_phi, z);
        // The entry face, by projected area, then a point on it. (The face as a sum of
        // comparisons, not branches: which one a ray takes is random, so branches mispredict.)
        double weights[3] = {std::fabs(d.x), std::fabs(d.y), std::fabs(d.z)};
        double pick = stream_.uniform01(i, 2) * (weights[0] + weights[1] + weights[2]);
        int axis = int(pick >= weights[0]) + int(pick >= weights[0] + weights[1]);
        glm::dvec3 p(stream_.uniform01(i, 3), stream_.uniform01(i, 4), stream_.uniform01(i, 5));
        p[axis] = d[axis] > 0 ? 0.0 : 1.0;
        return {glm::dvec3(voxel_) + p, d, exit_length(p, d)};
    }

private:
    // A node of the Fibonacci set before the voxel's turn: its angle's cos and sin, its
    // height z and the radius of its ring, sqrt(1 - z^2).
    struct fibonacci_node {
        double cos_a, sin_a, z, r;
    };
    static double ring_radius(double z) { return std::sqrt(std::max(0.0, 1.0 - z * z)); }

    glm::ivec3 voxel_;
    bool stratified_;
    voxel_stream stream_;
    double cos_turn_ = 1, sin_turn_ = 0;
    const fibonacci_node* nodes_ = nullptr;
};

}  // namespace voxray::appearance
