// What every backend's compositing walker hands its walk (appearance/walk.inc): the light,
// and a table's words as the kernel reads them (ordinal index, records, face pool, kind).
// The walkers (cpu/appearance_walk.hpp, opencl/appearance_walk.hpp,
// vulkan/appearance_walk.hpp) differ only in where these words live.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

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
};

namespace appearance {

// A table as the walk reads it. Never-empty word arrays: every backend needs a buffer.
struct walk_words {
    std::vector<std::uint32_t> index, records, faces;
    std::uint32_t kind = VX_APP_KIND_AVERAGES;

    explicit walk_words(const appearance_table& table) {
        check_table(table, "appearance walk: the table");
        index = ordinal_index(table), records = table.words, faces = table.faces, kind = kind_code(table.kind);
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
