// The *compact* record (ours; appearance/layout.h) of one voxel: its faces
// (appearance/faces.hpp) and its opacity along the 13 directions (appearance/opacity_rays.hpp).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "voxray/appearance/faces.hpp"
#include "voxray/appearance/layout.h"
#include "voxray/appearance/opacity_rays.hpp"
#include "voxray/appearance/record_codes.hpp"

namespace voxray::appearance {

struct compact_record {
    std::array<std::uint32_t, VX_APP_COMPACT_WORDS> head{};  // head[0], the first face, is set by the table
    std::vector<std::uint32_t> faces;                        // VX_APP_FACE_WORDS a face
};

// The ring's tangent for normals that stray `rms` radians: three equal nodes on a ring at
// angle a and the mean normal have the normals' second moment when (3/4) a^2 = rms^2.
inline double quadrature_spread(double rms) { return std::tan(std::min(std::sqrt(4.0 / 3.0) * rms, 1.1071487)); }

inline compact_record make_compact_record(const std::vector<voxel_face>& faces, const directional_opacities& alpha) {
    compact_record r;
    r.head[1] = std::uint32_t(faces.size());
    for (unsigned k = 0; k < VX_APP_DIRECTIONS; ++k) {
        std::uint32_t q = unorm(alpha[k], VX_APP_OPACITY_LEVELS);
        if (k < 6) r.head[1] |= q << (8 + 4 * k);
        else r.head[2] |= q << (4 * (k - 6));
    }
    for (const voxel_face& f : faces) {
        glm::vec2 e = octahedral(glm::vec3(f.normal));
        std::uint32_t weight = std::max<std::uint32_t>(1u, unorm(f.share, 255));
        std::uint32_t spread = unorm(quadrature_spread(f.rms_angle) / double(VX_APP_SPREAD_MAX), 255);
        std::uint32_t r8 = srgb_code(f.colour.r), g8 = srgb_code(f.colour.g), b8 = srgb_code(f.colour.b);
        r.faces.push_back(VX_APP_FACE_WORD0(r8, g8, b8, weight));
        r.faces.push_back(VX_APP_FACE_WORD1(snorm(e.x, 12), snorm(e.y, 12), spread));
    }
    return r;
}

}  // namespace voxray::appearance
