// An appearance table: one record per non-empty voxel of a model, in the order of the
// ordinal index (appearance/ordinal.h, built by ordinal_index.hpp), which maps any
// structure's hit voxel to its row. Records are
// `record_words` 32-bit words each (appearance/layout.h); compact records also own faces
// in a pool.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "voxray/appearance/layout.h"

namespace voxray::appearance {

// The table's row order, the ordinal index's (appearance/ordinal.h): bricks of 4^3 voxels in
// (z, y, x) order, then the voxels of a brick in (z, y, x) order.
inline bool ordinal_less(glm::ivec3 a, glm::ivec3 b) {
    auto key = [](glm::ivec3 p) {
        return std::array<int, 6>{p.z >> 2, p.y >> 2, p.x >> 2, p.z & 3, p.y & 3, p.x & 3};
    };
    return key(a) < key(b);
}

// The records a table can hold (layout.h).
enum class record_kind { averages, compact, six, sggx, faithful };

inline const char* record_name(record_kind k) {
    switch (k) {
    case record_kind::averages: return "averages";
    case record_kind::compact: return "compact";
    case record_kind::six: return "six";
    case record_kind::sggx: return "sggx";
    case record_kind::faithful: return "faithful";
    }
    return "unknown";
}

// Words a record of kind `k` takes (layout.h); 0 for a value outside the enum (a file's).
inline int record_words(record_kind k) {
    switch (k) {
    case record_kind::averages: return VX_APP_AVERAGES_WORDS;
    case record_kind::compact: return VX_APP_COMPACT_WORDS;
    case record_kind::six: return VX_APP_SIX_WORDS;
    case record_kind::sggx: return VX_APP_SGGX_WORDS;
    case record_kind::faithful: return VX_APP_FAITHFUL_WORDS;
    }
    return 0;
}

// Precomputed shadows (shadows.hpp): the light they are for and each row's visibility of
// it, round(255 v).
struct table_shadows {
    glm::vec3 to_light{0.0f, 1.0f, 0.0f};  // unit
    std::vector<std::uint8_t> visibility;  // a byte a row
};

struct appearance_table {
    record_kind kind = record_kind::averages;
    int record_words = 0;
    std::vector<glm::ivec3> voxels;     // sorted by ordinal_less
    std::vector<std::uint32_t> words;   // voxels.size() * record_words
    std::vector<std::uint32_t> faces;   // the compact records' face pool
    std::optional<table_shadows> shadows;

    std::size_t size() const { return voxels.size(); }
    std::span<const std::uint32_t> record(std::size_t row) const {
        return {words.data() + row * std::size_t(record_words), std::size_t(record_words)};
    }
    std::optional<std::size_t> row_of(glm::ivec3 voxel) const {
        auto it = std::lower_bound(voxels.begin(), voxels.end(), voxel, ordinal_less);
        if (it == voxels.end() || *it != voxel) return std::nullopt;
        return std::size_t(it - voxels.begin());
    }
    double bytes_per_voxel() const {
        std::size_t shadow_bytes = shadows ? shadows->visibility.size() : 0;
        return voxels.empty() ? 0.0
                              : (4.0 * double(words.size() + faces.size()) + double(shadow_bytes)) /
                                    double(voxels.size());
    }
};

}  // namespace voxray::appearance
