// Builds the ordinal index (appearance/ordinal_layout.h) of an appearance table's voxels, whose
// rows are in ordinal_less order (appearance/table.hpp).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "voxray/appearance/ordinal_layout.h"
#include "voxray/appearance/table.hpp"
#include "voxray/core/error.hpp"

namespace voxray::appearance {

inline std::vector<std::uint32_t> ordinal_index(const appearance_table& t) {
    std::vector<std::uint32_t> words(VX_APP_ORD_HEADER_WORDS, 0u);
    if (t.voxels.empty()) return words;  // 0 bricks: every lookup misses
    glm::ivec3 lo = t.voxels.front() >> 2, hi = lo;
    for (glm::ivec3 v : t.voxels) lo = glm::min(lo, v >> 2), hi = glm::max(hi, v >> 2);
    glm::i64vec3 bricks = glm::i64vec3(hi - lo) + std::int64_t(1);
    if (bricks.x * bricks.y * bricks.z > (std::int64_t(1) << 28))
        fail("appearance ordinal index: ", bricks.x, " x ", bricks.y, " x ", bricks.z, " bricks, over 2^28");
    glm::ivec3 origin = lo * 4;
    for (int a = 0; a < 3; ++a) words[a] = std::uint32_t(origin[a]), words[3 + a] = std::uint32_t(bricks[a]);
    std::size_t table = VX_APP_ORD_HEADER_WORDS, slots = std::size_t(bricks.x * bricks.y * bricks.z);
    words.resize(table + slots, VX_APP_NO_BRICK);
    words[6] = std::uint32_t(words.size());
    for (std::size_t row = 0; row < t.voxels.size(); ++row) {
        glm::ivec3 r = t.voxels[row] - origin;
        std::size_t slot = table + std::size_t(((r.z >> 2) * bricks.y + (r.y >> 2)) * bricks.x + (r.x >> 2));
        if (words[slot] == VX_APP_NO_BRICK) {  // rows are brick-major: a brick's first voxel comes first
            words[slot] = std::uint32_t((words.size() - words[6]) / VX_APP_ORD_RECORD_WORDS);
            words.insert(words.end(), {std::uint32_t(row), 0u, 0u});
        }
        unsigned bit = unsigned(VX_APP_BRICK_BIT(r.x, r.y, r.z));
        words[words[6] + words[slot] * VX_APP_ORD_RECORD_WORDS + 1 + bit / 32] |= 1u << (bit % 32);
    }
    if (words.size() > 0xFFFFFFFFull) fail("appearance ordinal index: ", words.size(), " words, over 2^32");
    return words;
}

}  // namespace voxray::appearance
