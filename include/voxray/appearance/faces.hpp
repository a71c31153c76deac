// A voxel's faces (our reading of the paper's virtual mesh, section 3.3): its samples'
// normals split by octant of their SGGX frame (appearance/sggx.hpp), and for each octant
// that holds samples one face: the mean normal, how far the normals stray from it, the mean
// colour and the share of the samples. The compact record stores these (layout.h).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "voxray/appearance/layout.h"
#include "voxray/appearance/sggx.hpp"
#include "voxray/appearance/voxel_sampler.hpp"

namespace voxray::appearance {

struct voxel_face {
    int octant = 0;
    glm::dvec3 normal{0, 0, 1};  // unit mean normal
    double rms_angle = 0;        // root mean square angle of the normals to the mean, radians
    glm::dvec4 colour{0.0};      // linear mean colour
    double share = 0;            // of the voxel's samples
};

// The faces of a voxel's samples, in octant order; none when it has no samples.
inline std::vector<voxel_face> voxel_faces(const voxel_samples& v) {
    std::vector<voxel_face> faces;
    if (v.seen.empty()) return faces;
    std::vector<glm::dvec3> normals;
    normals.reserve(v.seen.size());
    for (const surface_sample& s : v.seen) normals.push_back(glm::dvec3(s.normal));
    sggx_fit fit = fit_sggx(normals);
    std::array<std::vector<std::size_t>, VX_APP_MAX_FACES> members;
    for (std::size_t i = 0; i < normals.size(); ++i) members[std::size_t(fit.octant(normals[i]))].push_back(i);
    for (int o = 0; o < VX_APP_MAX_FACES; ++o) {
        const std::vector<std::size_t>& m = members[std::size_t(o)];
        if (m.empty()) continue;
        voxel_face f;
        f.octant = o;
        glm::dvec3 sum(0.0);
        for (std::size_t i : m) sum += normals[i], f.colour += glm::dvec4(v.seen[i].colour);
        double length = glm::length(sum);
        f.normal = length > 1e-9 ? sum / length : normals[m.front()];  // opposite normals cannot share an octant
        double squares = 0;
        for (std::size_t i : m) {
            double a = std::acos(std::clamp(glm::dot(normals[i], f.normal), -1.0, 1.0));
            squares += a * a;
        }
        f.rms_angle = std::sqrt(squares / double(m.size()));
        f.colour /= double(m.size());
        f.share = double(m.size()) / double(normals.size());
        faces.push_back(f);
    }
    return faces;
}

}  // namespace voxray::appearance
