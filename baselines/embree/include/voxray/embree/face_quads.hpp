// A voxel model's exposed faces as Embree quads: one quad per face whose neighbour is empty,
// with its own 4 vertices (Embree copies them into its BVH leaves anyway), wound so that the
// geometric normal points out of the voxel. Shared by the quad baseline (quad_scene.hpp) and
// the instanced one (instanced_scene.hpp).
#pragma once
#include <cstdint>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/vec3.hpp>

#include "voxray/core/error.hpp"
#include "voxray/embree/device.hpp"
#include "voxray/embree/exposure.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::embree {

// Primitive id i of a quad geometry maps to face i: the voxel, and VX_FACE_* in bits 0..7
// with the palette index in bits 8..15.
struct face_quad {
    glm::ivec3 voxel;
    std::uint32_t face_material;
};

inline std::vector<face_quad> exposed_faces(const voxel_model& model) {
    std::vector<face_quad> faces;
    for_each_voxel_exposure(model, [&](glm::ivec3 p, std::uint8_t material, std::uint8_t exposed) {
        for (std::uint32_t f = 0; f < 6; ++f)
            if (exposed & (1u << f)) faces.push_back({p, f | (std::uint32_t(material) << 8)});
    });
    faces.shrink_to_fit();
    // Vertex indices are 32-bit and each quad has 4 vertices of its own.
    check_limit("Embree face quads", faces.size(), std::size_t(1) << 30);
    return faces;
}

// Attaches the faces to `scene` as one committed quad geometry (high build quality).
inline void attach_face_quads(const device& dev, RTCScene scene, const std::vector<face_quad>& faces) {
    RTCGeometry g = rtcNewGeometry(dev.handle(), RTC_GEOMETRY_TYPE_QUAD);
    dev.check("rtcNewGeometry(QUAD)");
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4 * faces.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), faces.size()));
    dev.check("rtcSetNewGeometryBuffer");
    for (std::size_t q = 0; q < faces.size(); ++q) {
        const face_quad& f = faces[q];
        int face = int(f.face_material & 0xFFu);
        int a = face >> 1, u = (a + 1) % 3, w = (a + 2) % 3;
        glm::vec3 base(f.voxel);
        if (!(face & 1)) base[a] += 1.0f;  // positive faces lie on the far plane
        // Corners counter-clockwise seen from +a; negative faces are walked the other
        // way so that the geometric normal points out of the voxel.
        static constexpr int su[4] = {0, 1, 1, 0}, sw[4] = {0, 0, 1, 1};
        for (int k = 0; k < 4; ++k) {
            int c = (face & 1) ? 3 - k : k;
            glm::vec3 v = base;
            v[u] += float(su[c]);
            v[w] += float(sw[c]);
            float* out = vertices + 3 * (4 * q + std::size_t(k));
            out[0] = v.x, out[1] = v.y, out[2] = v.z;
            indices[4 * q + std::size_t(k)] = unsigned(4 * q + std::size_t(k));
        }
    }
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
    rtcCommitGeometry(g);
    rtcAttachGeometry(scene, g);
    rtcReleaseGeometry(g);
    dev.check("quad geometry setup");
}

}  // namespace voxray::embree
