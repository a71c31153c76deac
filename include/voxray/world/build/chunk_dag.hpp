// One chunk's DAG from its voxels: the svdag builder's merge and layout (svdag_build::
// assemble) over the fixed cube [0, C)^3, fed with leaves cut straight from the chunk's
// sorted voxels. A chunk's build reads nothing but its own voxels, so chunks build
// independently, in any order, on any thread or machine.
#pragma once
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "voxray/svdag/builder.hpp"
#include "voxray/svdag/morton.hpp"
#include "voxray/world/chunk.hpp"
#include "voxray/world/chunk_voxels.hpp"

namespace voxray {

// A chunk's attributes: exact (values are palette indices, kept as payload bytes) or
// colour blocks (values are RGBA8 colours) within colour_error.
struct chunk_dag_options {
    svdag_attributes attributes = svdag_attributes::exact;
    float colour_error = 0.05f;
};

inline chunk_record build_chunk(const chunk_voxels& voxels, chunk_key key, int chunk_bits, const chunk_dag_options& options) {
    if (chunk_bits < VX_WD_MIN_CHUNK_BITS || chunk_bits > VX_WD_MAX_CHUNK_BITS)
        fail("world: chunk_bits ", chunk_bits, " is outside [", VX_WD_MIN_CHUNK_BITS, ", ", VX_WD_MAX_CHUNK_BITS, "]");
    chunk_record out;
    out.key = key;
    out.chunk_bits = chunk_bits;
    out.voxel_count = voxels.size();

    // Depth-first order: by the leaf's Morton key, then the voxel's bit in the leaf.
    std::vector<std::pair<std::uint64_t, std::uint32_t>> order(voxels.size());
    for (std::size_t i = 0; i < voxels.size(); ++i) {
        glm::ivec3 p = chunk_voxels::position(voxels.keys[i]);
        out.solid_min = i ? glm::min(out.solid_min, p) : p;
        out.solid_max = i ? glm::max(out.solid_max, p) : p;
        std::uint64_t leaf = svdag_build::morton3(std::uint32_t(p.x >> 2), std::uint32_t(p.y >> 2), std::uint32_t(p.z >> 2));
        order[i] = {(leaf << 6) | std::uint64_t(VX_SV_LEAF_BIT(p.x, p.y, p.z)), std::uint32_t(i)};
    }
    std::sort(order.begin(), order.end());
    svdag_build::leaf_scan leaves;
    bool colours = options.attributes == svdag_attributes::colour_blocks;
    for (auto& [code, i] : order) {
        std::uint64_t leaf = code >> 6;
        if (leaves.keys.empty() || leaves.keys.back() != leaf) leaves.keys.push_back(leaf), leaves.masks.push_back(0);
        leaves.masks.back() |= std::uint64_t(1) << (code & 63);
        if (colours)
            leaves.colours.push_back(voxels.values[i]);
        else
            leaves.payload.push_back(std::uint8_t(voxels.values[i]));
    }
    svdag_options dag;
    dag.attributes = options.attributes;
    dag.colour_error = options.colour_error;
    dag.threads = 1;  // chunks are the unit of parallelism
    svdag_build::dag_frame frame{glm::ivec3(0), glm::ivec3(1 << chunk_bits), glm::ivec3(0), chunk_bits};
    out.dag = svdag_build::assemble(std::move(leaves), frame, dag, nullptr).words;
    return out;
}

}  // namespace voxray
