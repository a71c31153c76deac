// Small seeded models for tests: sparse noise, solid blocks, hollow boxes, a sphere shell,
// a single voxel; all may sit at negative coordinates. Shared by every test folder.
#pragma once
#include <cmath>
#include <string>
#include <vector>

#include "voxray/check/ray_sets.hpp"
#include "voxray/core/box.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::test {

// Each voxel of a size^3 cube at `offset` is solid with probability `density`.
inline voxel_model random_model(int size, float density, std::uint64_t seed, glm::ivec3 offset = glm::ivec3(0)) {
    voxel_model m;
    rng g(seed);
    for (int z = 0; z < size; ++z)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                if (g.uniform() < density) m.set(offset + glm::ivec3(x, y, z), std::uint8_t(1 + g.below(255)));
    return m;
}

// A sparse 40^3 random model at an odd offset: what the user-kernel, user-shader and
// interop tests trace.
inline voxel_model offset_random_scene() { return random_model(40, 0.04f, 5, {-9, 2, -17}); }

// `count` voxels at random places of box b (repeats allowed), random materials.
inline voxel_model random_sparse(box3i b, int count, std::uint64_t seed) {
    voxel_model m;
    rng g(seed);
    glm::ivec3 e = b.extent();
    for (int i = 0; i < count; ++i)
        m.set(b.min + glm::ivec3(g.below(e.x), g.below(e.y), g.below(e.z)), std::uint8_t(1 + g.below(255)));
    return m;
}

// The one-voxel-thick shell of box b, materials varying with position.
inline voxel_model hollow_box(box3i b) {
    voxel_model m;
    for (int z = b.min.z; z < b.max.z; ++z)
        for (int y = b.min.y; y < b.max.y; ++y)
            for (int x = b.min.x; x < b.max.x; ++x) {
                bool shell = x == b.min.x || y == b.min.y || z == b.min.z || x == b.max.x - 1 || y == b.max.y - 1 ||
                             z == b.max.z - 1;
                if (shell) m.set({x, y, z}, std::uint8_t(1 + (x * 5 + y + z * 11) % 250));
            }
    return m;
}

inline voxel_model hollow_box(int size, glm::ivec3 offset = glm::ivec3(0)) {
    return hollow_box(box3i{offset, offset + size});
}

// Every voxel of [lo, hi) solid with one material.
inline voxel_model solid_block(glm::ivec3 lo, glm::ivec3 hi, std::uint8_t material = 9) {
    voxel_model m;
    for (int z = lo.z; z < hi.z; ++z)
        for (int y = lo.y; y < hi.y; ++y)
            for (int x = lo.x; x < hi.x; ++x) m.set({x, y, z}, material);
    return m;
}

// Every voxel of [lo, hi) solid, materials varying with position (no uniform bricks).
inline voxel_model patterned_block(glm::ivec3 lo, glm::ivec3 hi) {
    voxel_model m;
    for (int z = lo.z; z < hi.z; ++z)
        for (int y = lo.y; y < hi.y; ++y)
            for (int x = lo.x; x < hi.x; ++x) m.set({x, y, z}, std::uint8_t(1 + (x + 3 * y + 7 * z) % 200));
    return m;
}

inline voxel_model single_voxel(glm::ivec3 p, std::uint8_t material = 42) {
    voxel_model m;
    m.set(p, material);
    return m;
}

// A sphere shell one voxel thick around the origin: about 4 pi r^2 voxels (r = 89: ~100k).
inline voxel_model sphere_shell(int r) {
    voxel_model m;
    for (int z = -r - 1; z <= r + 1; ++z)
        for (int y = -r - 1; y <= r + 1; ++y)
            for (int x = -r - 1; x <= r + 1; ++x) {
                float d = std::sqrt(float(x * x + y * y + z * z));
                if (d >= r - 0.5f && d < r + 0.5f) m.set({x, y, z}, std::uint8_t(1 + (x & 127)));
            }
    return m;
}

struct named_model {
    std::string name;
    voxel_model model;
};

// The mix the backend tests trace: sparse and multi-chunk noise, blocks, shells, one
// voxel, and models below and across zero.
inline std::vector<named_model> backend_models() {
    std::vector<named_model> out;
    out.push_back({"random_sparse", random_sparse({{0, 0, 0}, {40, 40, 40}}, 3000, 1)});
    out.push_back({"random_multi_chunk", random_sparse({{0, 0, 0}, {70, 35, 50}}, 6000, 2)});
    out.push_back({"patterned_block", patterned_block({3, -2, 5}, {23, 10, 14})});
    out.push_back({"hollow_box", hollow_box({{3, 2, 1}, {27, 26, 25}})});
    out.push_back({"single_voxel", single_voxel({5, -3, 7})});
    out.push_back({"negative_sparse", random_sparse({{-60, -45, -33}, {-10, -5, -2}}, 3000, 3)});
    out.push_back({"straddling_zero", random_sparse({{-20, -17, -9}, {21, 14, 30}}, 4000, 4)});
    out.push_back({"negative_hollow", hollow_box({{-40, -30, -20}, {-18, -12, -1}})});
    return out;
}

}  // namespace voxray::test
