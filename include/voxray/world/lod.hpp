// The LOD chain (Aokana, section 3.4): the 8 chunks of LOD n-1 in a (2C)^3 region make
// one chunk of LOD n at the same C^3 resolution. A LOD n voxel exists where at least
// `density` of its 8 children do; its value is their average colour (colour worlds) or,
// since palette indices cannot be averaged, their most frequent index, the smallest
// among equals (exact worlds).
#pragma once
#include <array>
#include <cstdint>
#include <utility>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/world/chunk_voxels.hpp"

namespace voxray {

// children[o]: the child chunk of octant o = x | y << 1 | z << 2 (nullptr when empty).
inline chunk_voxels downsample(const std::array<const chunk_voxels*, 8>& children, int chunk_bits, int density,
                               bool colours) {
    if (density < 1 || density > 8) fail("world: LOD density ", density, " is outside [1, 8] (children of 8)");
    int half = 1 << (chunk_bits - 1);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> parents;  // (parent key, child value)
    for (unsigned o = 0; o < 8; ++o) {
        const chunk_voxels* c = children[o];
        if (!c) continue;
        glm::ivec3 offset = glm::ivec3(int(o & 1u), int((o >> 1) & 1u), int((o >> 2) & 1u)) * half;
        for (std::size_t i = 0; i < c->size(); ++i)
            parents.emplace_back(chunk_voxels::key(offset + (chunk_voxels::position(c->keys[i]) >> 1)), c->values[i]);
    }
    std::sort(parents.begin(), parents.end());
    chunk_voxels out;
    for (std::size_t a = 0; a < parents.size();) {
        std::size_t b = a;
        while (b < parents.size() && parents[b].first == parents[a].first) ++b;
        if (int(b - a) >= density) {
            std::uint32_t value;
            if (colours) {
                std::array<std::uint32_t, 4> sum{};
                for (std::size_t i = a; i < b; ++i)
                    for (int k = 0; k < 4; ++k) sum[std::size_t(k)] += (parents[i].second >> (8 * k)) & 255u;
                value = 0;
                auto n = std::uint32_t(b - a);
                for (int k = 0; k < 4; ++k) value |= ((sum[std::size_t(k)] + n / 2) / n) << (8 * k);
            } else {
                // Sorted pairs: equal values are adjacent; the first longest run wins.
                value = parents[a].second;
                std::size_t best = 0;
                for (std::size_t i = a; i < b;) {
                    std::size_t j = i;
                    while (j < b && parents[j].second == parents[i].second) ++j;
                    if (j - i > best) best = j - i, value = parents[i].second;
                    i = j;
                }
            }
            out.keys.push_back(parents[a].first);
            out.values.push_back(value);
        }
        a = b;
    }
    return out;
}

}  // namespace voxray
