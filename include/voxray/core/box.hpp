// Integer voxel boxes: min inclusive, max exclusive.
#pragma once
#include <algorithm>
#include <cstdint>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace voxray {

struct box3i {
    glm::ivec3 min{0};
    glm::ivec3 max{0};  // exclusive

    bool empty() const { return max.x <= min.x || max.y <= min.y || max.z <= min.z; }
    glm::ivec3 extent() const { return empty() ? glm::ivec3(0) : max - min; }
    bool contains(glm::ivec3 p) const {
        return p.x >= min.x && p.y >= min.y && p.z >= min.z && p.x < max.x && p.y < max.y && p.z < max.z;
    }
    std::uint64_t volume() const {
        auto e = extent();
        return std::uint64_t(e.x) * std::uint64_t(e.y) * std::uint64_t(e.z);
    }
    // Grows the box to include voxel p.
    void include(glm::ivec3 p) {
        if (empty()) { min = p; max = p + 1; return; }
        min = glm::min(min, p);
        max = glm::max(max, p + 1);
    }
    void include(const box3i& b) {
        if (b.empty()) return;
        if (empty()) { *this = b; return; }
        min = glm::min(min, b.min);
        max = glm::max(max, b.max);
    }
};

}  // namespace voxray
