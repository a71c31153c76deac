// What every backend's compositing walker hands its walk (appearance/walk.inc): the light,
// and a table's words as the kernel reads them (ordinal index, records and shadows, face
// pool, kind).
// The walkers (cpu/appearance_walk.hpp, opencl/appearance_walk.hpp,
// vulkan/appearance_walk.hpp) differ only in where these words live.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>
#include <glm/vector_relational.hpp>

#include "voxray/appearance/ordinal_index.hpp"
#include "voxray/appearance/pixel.hpp"
#include "voxray/appearance/table.hpp"
#include "voxray/appearance/table_check.hpp"
#include "voxray/core/error.hpp"

namespace voxray {

struct appearance_light {
    glm::vec3 to_light{0.0f, 1.0f, 0.0f};  // unit
    float ambient = 0.2f;
    float cutoff = 1e-3f;  // stop below this transmittance (the paper's)
    std::uint32_t max_visits = 4096;
    // Light voxels by the table's precomputed shadows (appearance/shadows.hpp) where it has
    // them; they must then be for this light (to_light).
    bool shadows = true;
};

namespace appearance {

// Where a table's precomputed shadows are in the walk's `records` (word `at` on; 0: none)
// and the light they are for.
struct walk_shadows {
    std::uint32_t at = 0;
    glm::vec3 to_light{0.0f};

    // The walk's `shadows_at` for `light`: 0 where it takes no shadows. Throws where it
    // takes them and they are for another light.
    std::uint32_t at_for(const appearance_light& light) const {
        if (at == 0 || !light.shadows) return 0;
        if (glm::any(glm::greaterThan(glm::abs(light.to_light - to_light), glm::vec3(1e-6f))))
            fail("appearance walk: the table's shadows are for the light towards (", to_light.x, ", ", to_light.y,
                 ", ", to_light.z, "), the walk's light is towards (", light.to_light.x, ", ", light.to_light.y, ", ",
                 light.to_light.z, "): precompute them for it, or walk with shadows off");
        return at;
    }
};

// A table as the walk reads it. Never-empty word arrays: every backend needs a buffer.
// Precomputed shadows follow the records in `records`: a byte a row, four a word.
struct walk_words {
    std::vector<std::uint32_t> index, records, faces;
    std::uint32_t kind = VX_APP_KIND_AVERAGES;
    walk_shadows shadows;

    explicit walk_words(const appearance_table& table) {
        check_table(table, "appearance walk: the table");
        index = ordinal_index(table), records = table.words, faces = table.faces, kind = kind_code(table.kind);
        if (table.shadows && !table.voxels.empty()) {
            if (records.size() + table.size() / 4 + 1 > 0xFFFFFFFFull)
                fail("appearance walk: ", records.size(), " record words and shadows are above 2^32 words");
            shadows = {std::uint32_t(records.size()), table.shadows->to_light};
            records.resize(records.size() + (table.size() + 3) / 4, 0);
            for (std::size_t row = 0; row < table.size(); ++row)
                records[shadows.at + row / 4] |= std::uint32_t(table.shadows->visibility[row]) << (8 * (row % 4));
        }
        if (records.empty()) records.push_back(0);
        if (faces.empty()) faces.push_back(0);
    }

    static std::uint32_t kind_code(record_kind k) {
        switch (k) {
        case record_kind::averages: return VX_APP_KIND_AVERAGES;
        case record_kind::compact: return VX_APP_KIND_COMPACT;
        case record_kind::six: return VX_APP_KIND_SIX;
        case record_kind::sggx: return VX_APP_KIND_SGGX;
        case record_kind::faithful: return VX_APP_KIND_FAITHFUL;
        }
        fail("appearance walk: unknown record kind ", int(k));
    }
};

// Throws for the first pixel whose walk met a voxel the table has no row for.
inline void check_walked(std::span<const appearance_pixel> pixels) {
    for (const appearance_pixel& p : pixels)
        if (p.status == VX_APP_WALK_NO_RECORD)
            fail("appearance walk: voxel (", p.x, ", ", p.y, ", ", p.z,
                 ") of the structure has no row in the appearance table (a table of other voxels?)");
}

}  // namespace appearance
}  // namespace voxray
