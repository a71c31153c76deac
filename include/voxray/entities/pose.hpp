// Where an instance stands: position, rotation and uniform scale, and the words the
// kernels read for it (entities/layout.h). The model's centre (the middle of its box) is
// the pivot: it lands on `position`, and the model turns and scales about it.
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>

#include <glm/gtc/quaternion.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include "voxray/core/error.hpp"
#include "voxray/entities/layout.h"

namespace voxray {

struct pose {
    glm::vec3 position{0.0f};                      // world voxels
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};    // w, x, y, z; normalised when placed
    float scale = 1.0f;                            // uniform, > 0
};

// The pose with its rotation normalised; a zero, NaN or infinite rotation, a scale
// that is not a finite positive number, or a non-finite position is an error naming it.
inline pose checked_pose(pose p) {
    auto finite = [](float v) { return std::isfinite(v); };
    if (!finite(p.position.x) || !finite(p.position.y) || !finite(p.position.z))
        fail("entity pose: position (", p.position.x, ", ", p.position.y, ", ", p.position.z, ") is not finite");
    if (!finite(p.scale) || !(p.scale > 0.0f))
        fail("entity pose: scale ", p.scale, " is not a finite number above 0");
    glm::dquat q(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z);
    double norm = std::sqrt(q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z);
    if (!std::isfinite(norm) || norm < 1e-12)
        fail("entity pose: rotation (w ", p.rotation.w, ", x ", p.rotation.x, ", y ", p.rotation.y, ", z ",
             p.rotation.z, ") cannot be normalised (zero, NaN or infinite)");
    q = q / norm;
    p.rotation = glm::quat(float(q.w), float(q.x), float(q.y), float(q.z));
    return p;
}

// Model -> world rotation times scale, in double (the box and the words derive from it).
inline glm::dmat3 model_to_world(const pose& p) {
    return glm::mat3_cast(glm::dquat(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)) * double(p.scale);
}

// The instance words of a placed model whose box is `extent` voxels (its centre is the
// pivot), with the model record at word `model_offset` (entities/layout.h).
inline std::array<std::uint32_t, VX_SC_INSTANCE_WORDS> instance_words(const pose& p, glm::ivec3 extent,
                                                                       std::uint32_t model_offset) {
    glm::dmat3 to_model = glm::transpose(glm::mat3_cast(glm::dquat(p.rotation.w, p.rotation.x, p.rotation.y,
                                                                   p.rotation.z))) / double(p.scale);
    std::array<float, VX_SC_INSTANCE_WORDS> f{};
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) f[VX_SC_INSTANCE_M + 3 * row + col] = float(to_model[col][row]);  // glm: [column][row]
    for (int a = 0; a < 3; ++a) {
        f[VX_SC_INSTANCE_P + a] = p.position[a];
        f[VX_SC_INSTANCE_C + a] = float(extent[a]) * 0.5f;
    }
    std::array<std::uint32_t, VX_SC_INSTANCE_WORDS> words{};
    for (int k = 0; k < VX_SC_INSTANCE_WORDS; ++k) words[k] = std::bit_cast<std::uint32_t>(f[k]);
    words[VX_SC_INSTANCE_MODEL] = model_offset;
    return words;
}

// The world box (min, max) of a placed model of `extent` voxels, widened by a margin that
// covers the float rounding of the kernels' transform, so the BVH never culls a box whose
// model walk could hit.
struct world_box {
    glm::vec3 min{0.0f}, max{0.0f};
};
inline world_box placed_box(const pose& p, glm::ivec3 extent) {
    glm::dmat3 m = model_to_world(p);
    glm::dvec3 half = glm::dvec3(extent) * 0.5;
    // |M| * half: the half-extent of the rotated box along each world axis.
    glm::dvec3 reach(0.0);
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col) reach[row] += std::abs(m[col][row]) * half[col];
    glm::dvec3 centre(p.position);
    double size = std::max({std::abs(centre.x), std::abs(centre.y), std::abs(centre.z)}) + glm::length(reach);
    double margin = 1e-3 + 1e-5 * size;
    world_box b;
    b.min = glm::vec3(centre - reach - margin);
    b.max = glm::vec3(centre + reach + margin);
    return b;
}

}  // namespace voxray
