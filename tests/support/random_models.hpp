// Small seeded models for tests: sparse noise, a solid block, a hollow box, negative coordinates.
#pragma once
#include "voxray/check/ray_sets.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::test {

inline voxel_model random_model(int size, float density, std::uint64_t seed, glm::ivec3 offset = glm::ivec3(0)) {
    voxel_model m;
    rng g(seed);
    for (int z = 0; z < size; ++z)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x)
                if (g.uniform() < density) m.set(offset + glm::ivec3(x, y, z), std::uint8_t(1 + g.below(255)));
    return m;
}

inline voxel_model hollow_box(int size, glm::ivec3 offset = glm::ivec3(0)) {
    voxel_model m;
    for (int z = 0; z < size; ++z)
        for (int y = 0; y < size; ++y)
            for (int x = 0; x < size; ++x) {
                bool shell = x == 0 || y == 0 || z == 0 || x == size - 1 || y == size - 1 || z == size - 1;
                if (shell) m.set(offset + glm::ivec3(x, y, z), std::uint8_t(1 + (x + y + z) % 200));
            }
    return m;
}

inline voxel_model solid_block(glm::ivec3 lo, glm::ivec3 hi, std::uint8_t material = 9) {
    voxel_model m;
    for (int z = lo.z; z < hi.z; ++z)
        for (int y = lo.y; y < hi.y; ++y)
            for (int x = lo.x; x < hi.x; ++x) m.set({x, y, z}, material);
    return m;
}

}  // namespace voxray::test
