// A chunk's solid voxels while a world is built: in the chunk's own voxel coordinates
// [0, C)^3, each with one value, a palette index (exact worlds) or an RGBA8 colour (colour
// worlds, whose coarse LODs average colours). Sorted by key, so equal content compares
// equal and lookups are binary searches.
#pragma once
#include <algorithm>
#include <cstdint>
#include <map>
#include <vector>

#include <glm/glm.hpp>

#include "voxray/core/ivec3_less.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/world/chunk.hpp"

namespace voxray {

struct chunk_voxels {
    std::vector<std::uint32_t> keys;    // pack_chunk_voxel(x, y, z), ascending
    std::vector<std::uint32_t> values;

    std::size_t size() const { return keys.size(); }
    bool empty() const { return keys.empty(); }
    static std::uint32_t key(glm::ivec3 p) { return pack_chunk_voxel(p); }
    static glm::ivec3 position(std::uint32_t k) { return unpack_chunk_voxel(k); }
    // Sorts (key, value) pairs appended in any order.
    void sort() {
        std::vector<std::size_t> order(keys.size());
        for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
        std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return keys[a] < keys[b]; });
        chunk_voxels sorted;
        sorted.keys.reserve(keys.size());
        sorted.values.reserve(keys.size());
        for (auto i : order) sorted.keys.push_back(keys[i]), sorted.values.push_back(values[i]);
        *this = std::move(sorted);
    }
};

// Which cell (C = 2^chunk_bits voxels a side, from `origin`) a position lies in.
inline glm::ivec3 cell_of(glm::ivec3 p, glm::ivec3 origin, int chunk_bits) { return (p - origin) >> chunk_bits; }

// The model's voxels cut into the cells of a grid whose cell (0,0,0) starts at `origin`,
// each in its cell's coordinates. `colours`: values are the palette colours (RGBA8), else
// the palette indices. One pass over the model's 16^3 chunks (a cell holds whole ones).
inline std::map<glm::ivec3, chunk_voxels, ivec3_less> cut_into_cells(const voxel_model& model, glm::ivec3 origin,
                                                                     int chunk_bits, bool colours) {
    std::map<glm::ivec3, chunk_voxels, ivec3_less> cells;
    int mask = (1 << chunk_bits) - 1;
    model.for_each_chunk([&](glm::ivec3 chunk_origin, const voxel_model::chunk& c) {
        glm::ivec3 cell = cell_of(chunk_origin, origin, chunk_bits);
        chunk_voxels& out = cells[cell];
        glm::ivec3 local0 = (chunk_origin - origin) & mask;
        for (int i = 0; i < voxel_model::chunk_voxels; ++i) {
            std::uint8_t v = c.voxels[std::size_t(i)];
            if (!v) continue;
            out.keys.push_back(chunk_voxels::key(local0 + voxel_model::local_position(i)));
            out.values.push_back(colours ? pack_rgba(model.palette()[v].colour) : v);
        }
    });
    for (auto& [cell, v] : cells) v.sort();
    return cells;
}

}  // namespace voxray
