// An appearance table: one record per non-empty voxel of a model, in the order of the
// voxels' ordinal, here (z, y, x) order of their coordinates; a structure that numbers its
// voxels otherwise (a DAG's depth-first index) maps its ordinal to a row. Records are
// `record_words` 32-bit words each (appearance/layout.h).
#pragma once
#include <algorithm>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

namespace voxray::appearance {

inline bool zyx_less(glm::ivec3 a, glm::ivec3 b) {
    if (a.z != b.z) return a.z < b.z;
    if (a.y != b.y) return a.y < b.y;
    return a.x < b.x;
}

struct appearance_table {
    int record_words = 0;
    std::vector<glm::ivec3> voxels;     // sorted by zyx_less
    std::vector<std::uint32_t> words;   // voxels.size() * record_words

    std::size_t size() const { return voxels.size(); }
    std::span<const std::uint32_t> record(std::size_t row) const {
        return {words.data() + row * std::size_t(record_words), std::size_t(record_words)};
    }
    std::optional<std::size_t> row_of(glm::ivec3 voxel) const {
        auto it = std::lower_bound(voxels.begin(), voxels.end(), voxel, zyx_less);
        if (it == voxels.end() || *it != voxel) return std::nullopt;
        return std::size_t(it - voxels.begin());
    }
    double bytes_per_voxel() const { return 4.0 * record_words; }
};

}  // namespace voxray::appearance
