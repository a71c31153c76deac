// Tables and rays the walk tests share (test_walk.cpp, test_walk_backends.cpp).
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "voxray/appearance/compact.hpp"
#include "voxray/appearance/table.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/rays/camera.hpp"

namespace voxray::test {

// A compact table of `model`'s voxels, every one with the same opacity (0..15) and one face
// of a colour that depends on the voxel, turned to -z.
inline appearance::appearance_table uniform_table(const voxel_model& model, std::uint32_t opacity_q) {
    using namespace appearance;
    appearance_table t;
    t.kind = record_kind::compact;
    t.record_words = VX_APP_COMPACT_WORDS;
    model.for_each_voxel([&](glm::ivec3 p, std::uint8_t) { t.voxels.push_back(p); });
    std::sort(t.voxels.begin(), t.voxels.end(), ordinal_less);
    for (std::size_t row = 0; row < t.voxels.size(); ++row) {
        std::uint32_t h1 = 1u, h2 = 0u;
        for (unsigned k = 0; k < 6; ++k) h1 |= opacity_q << (8 + 4 * k);
        for (unsigned k = 6; k < VX_APP_DIRECTIONS; ++k) h2 |= opacity_q << (4 * (k - 6));
        t.words.insert(t.words.end(), {std::uint32_t(row), h1, h2});
        glm::ivec3 v = t.voxels[row];
        std::uint32_t r = std::uint32_t(v.x * 37) & 255u, g = std::uint32_t(v.y * 53) & 255u, b = 200u;
        glm::vec2 e = octahedral({0, 0, -1});
        t.faces.insert(t.faces.end(),
                       {VX_APP_FACE_WORD0(r, g, b, 255u), VX_APP_FACE_WORD1(snorm(e.x, 12), snorm(e.y, 12), 0u)});
    }
    return t;
}

inline std::vector<ray> camera_rays(const voxel_model& model, int size) {
    return primary_rays(auto_camera(model.bounds(), 1, 1), size, size);
}

}  // namespace voxray::test
