// The voxels a sparse voxel DAG blob holds, read back in depth-first order: position in
// the DAG's cube and attribute (the payload byte, or the RGBA8 colour of the voxel's
// block). For what reads a built DAG again: the chunked world's LOD build from chunk files,
// and tests. The blob must be valid (svdag/validate.hpp for untrusted ones).
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "voxray/svdag/layout.h"

namespace voxray {

struct decoded_voxel {
    glm::ivec3 position;     // in the DAG's cube [0, 2^D)^3
    std::uint32_t attribute;
};

inline std::vector<decoded_voxel> decode_svdag(std::span<const std::uint32_t> w) {
    std::vector<decoded_voxel> out;
    int depth = int(w[VX_SV_HEADER_DEPTH]);
    int leaf_depth = depth - VX_SV_LEAF_EDGE_BITS;
    // Depth first, octants in order: the order of the attributes.
    struct frame { std::uint32_t node; int level; glm::ivec3 at; };
    std::vector<frame> stack{{w[VX_SV_HEADER_ROOT], 0, glm::ivec3(0)}};
    while (!stack.empty()) {
        frame f = stack.back();
        stack.pop_back();
        if (f.level == leaf_depth) {
            std::uint64_t mask = std::uint64_t(w[f.node]) | (std::uint64_t(w[f.node + 1]) << 32);
            for (std::uint32_t i = 0; i < 64; ++i)
                if (mask >> i & 1u) out.push_back({f.at + glm::ivec3(int(i & 3u), int((i >> 2) & 3u), int(i >> 4)), 0u});
            continue;
        }
        std::uint32_t mask = w[f.node] & VX_SV_NODE_MASK_BITS;
        int half = 1 << (depth - 1 - f.level);
        // Pushed in reverse, so the lowest octant is taken first.
        for (int o = 7; o >= 0; --o) {
            if (!(mask >> o & 1u)) continue;
            std::uint32_t slot = std::uint32_t(std::popcount(mask & ((1u << o) - 1u)));
            glm::ivec3 offset = glm::ivec3(o & 1, (o >> 1) & 1, (o >> 2) & 1) * half;
            stack.push_back({w[f.node + VX_SV_NODE_CHILDREN + slot], f.level + 1, f.at + offset});
        }
    }
    std::uint32_t attributes = w[VX_SV_HEADER_ATTRIBUTES];
    if (w[VX_SV_HEADER_ATTRIBUTE_KIND] == VX_SV_ATTRIBUTES_EXACT) {
        for (std::size_t i = 0; i < out.size(); ++i)
            out[i].attribute = (w[attributes + VX_SV_ATTRIBUTE_WORD(i)] >> VX_SV_ATTRIBUTE_SHIFT(i)) & 255u;
    } else {
        std::uint32_t blocks = w[VX_SV_HEADER_ATTRIBUTE_COUNT], colours = w[VX_SV_HEADER_COLOURS];
        std::uint32_t block = 0;
        for (std::size_t i = 0; i < out.size(); ++i) {
            while (block + 1 < blocks && w[attributes + block + 1] <= i) ++block;
            out[i].attribute = w[colours + block];
        }
    }
    return out;
}

}  // namespace voxray
