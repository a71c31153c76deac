// A triangle mesh as an Embree scene in voxel space (the voxelizer's grid map applied to its
// positions, so rays and voxel coordinates need no conversion), robust mode on, and its
// first hit along a ray segment. Shared by the solid fill (solid_fill.hpp) and the
// appearance precompute's sampling rays (voxray/appearance/precompute.hpp).
#pragma once
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/vec3.hpp>

#include "voxray/core/error.hpp"
#include "voxray/embree/device.hpp"
#include "voxray/io/mesh.hpp"
#include "voxray/io/voxelizer.hpp"

namespace voxray::embree {

struct triangle_hit {
    float t = 0;
    std::uint32_t triangle = 0;
    glm::dvec3 barycentric{1, 0, 0};  // weights of the triangle's three corners
    glm::vec3 normal{0, 0, 1};        // geometric normal, unit length, wound as the triangle
};

class triangle_scene {
public:
    triangle_scene(const io::triangle_mesh& mesh, const io::voxel_grid_map& grid)
        : scene_(rtcNewScene(device_.handle())) {
        device_.check("rtcNewScene");
        rtcSetSceneFlags(scene_.get(), RTC_SCENE_FLAG_ROBUST);
        RTCGeometry geom = rtcNewGeometry(device_.handle(), RTC_GEOMETRY_TYPE_TRIANGLE);
        device_.check("rtcNewGeometry");
        auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                               3 * sizeof(float), mesh.positions.size()));
        auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                  3 * sizeof(unsigned), mesh.triangles.size()));
        if (!vb || !ib) {
            rtcReleaseGeometry(geom);
            device_.check("rtcSetNewGeometryBuffer");
            fail("Embree could not allocate the buffers of a mesh of ", mesh.triangles.size(), " triangles");
        }
        for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
            auto p = grid.to_voxel(mesh.positions[i]);
            for (int k = 0; k < 3; ++k) vb[3 * i + k] = float(p[k]);
        }
        vertices_ = vb, indices_ = ib;  // Embree's own buffers, alive as long as the scene
        for (std::size_t i = 0; i < mesh.triangles.size(); ++i)
            for (int k = 0; k < 3; ++k) ib[3 * i + k] = mesh.triangles[i][k];
        rtcCommitGeometry(geom);
        rtcAttachGeometry(scene_.get(), geom);
        rtcReleaseGeometry(geom);
        rtcCommitScene(scene_.get());
        device_.check("rtcCommitScene");
    }

    RTCScene handle() const { return scene_.get(); }

    // The first hit of the ray org + t dir with t in [tnear, tfar], if any. Thread-safe.
    std::optional<triangle_hit> first_hit(glm::vec3 org, glm::vec3 dir, float tnear, float tfar) const {
        RTCIntersectContext ctx;
        rtcInitIntersectContext(&ctx);
        RTCRayHit rh{};
        rh.ray.org_x = org.x, rh.ray.org_y = org.y, rh.ray.org_z = org.z;
        rh.ray.dir_x = dir.x, rh.ray.dir_y = dir.y, rh.ray.dir_z = dir.z;
        rh.ray.tnear = tnear, rh.ray.tfar = tfar, rh.ray.mask = ~0u;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene_.get(), &ctx, &rh);
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
        triangle_hit h;
        h.t = rh.ray.tfar;
        h.triangle = rh.hit.primID;
        h.barycentric = {1.0 - double(rh.hit.u) - double(rh.hit.v), double(rh.hit.u), double(rh.hit.v)};
        glm::vec3 n(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
        float length = std::sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
        h.normal = length > 0 ? n / length : glm::vec3(0, 0, 1);
        return h;
    }

    // Appends to `out` the triangles whose bounds in the BVH meet the ball of `radius` about
    // `centre`: a superset of those that reach any region inside the ball. Thread-safe.
    void triangles_near(glm::vec3 centre, float radius, std::vector<std::uint32_t>& out) const {
        RTCPointQuery query{};
        query.x = centre.x, query.y = centre.y, query.z = centre.z, query.radius = radius;
        RTCPointQueryContext context;
        rtcInitPointQueryContext(&context);
        rtcPointQuery(scene_.get(), &query, &context, collect_triangle, &out);
    }

    // Triangle `t`'s corners in voxel space, exactly as Embree holds them.
    std::array<glm::vec3, 3> corners(std::uint32_t t) const {
        auto corner = [&](int k) {
            const float* v = vertices_ + 3 * std::size_t(indices_[3 * std::size_t(t) + std::size_t(k)]);
            return glm::vec3(v[0], v[1], v[2]);
        };
        return {corner(0), corner(1), corner(2)};
    }

private:
    static bool collect_triangle(RTCPointQueryFunctionArguments* args) {
        static_cast<std::vector<std::uint32_t>*>(args->userPtr)->push_back(args->primID);
        return false;  // the query's ball stays as it is
    }

    device device_;
    scene_handle scene_;
    const float* vertices_ = nullptr;    // voxel space, 3 a vertex
    const unsigned* indices_ = nullptr;  // 3 a triangle
};

}  // namespace voxray::embree
