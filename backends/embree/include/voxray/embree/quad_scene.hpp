// Embree baseline 1: one quad per exposed voxel face (a face whose neighbour is empty),
// RTC_GEOMETRY_TYPE_QUAD, robust (watertight) mode, high build quality. Primitive id i maps
// to faces_[i] = (voxel, face, material).
//
// LIMITATION: a ray that starts inside solid cannot be detected — it sees only the inner side
// of the solid's surface quads. This baseline is for speed and is compared with the reference
// only on rays whose start point lies outside solid voxels; for those the result follows the
// contract (first voxel entered, entry face, material; t from Embree's quad test, within
// float rounding of the exact plane crossing).
//
// Two degenerate cases would otherwise differ from the reference DDA:
//  - A ray that starts exactly on a voxel boundary plane: Embree accepts a hit at t = tnear
//    on both sides of the plane, so a ray leaving a solid voxel's face would hit that face
//    from behind.
//  - A ray running exactly along a plane x = k (zero x direction): the reference puts it in
//    voxel column k (voxel x covers [x, x+1)), but Embree's watertight test also hits the
//    quads of column k-1, whose edge lies on the ray.
// Both need a start point with an integer coordinate, so only packets holding such a ray
// pay for a fix: those lanes are rebased to start at tnear 0 (so a plane through the start
// has t = 0 exactly), and the packet is traced with a context filter that rejects back-face
// hits (a ray from outside solid can only enter a voxel through a front face) and hits on a
// voxel whose half-open extent does not contain the ray's coordinate along a zero-direction
// axis. Other packets run unfiltered.
//
// Results:
//  - closest_hit: status, t (+ rounding), voxel, face, material; steps = 0.
//  - any_hit: status only. On a hit, t = NaN (unknown: Embree stops at any occluder and
//    does not say which), voxel = 0, face = none, material = 0.
//  - bytes(): Embree's allocations for this scene (vertex/index buffers, BVH with its copies
//    of the quads), measured by the device's memory monitor across the build, plus faces_
//    (16 bytes a quad). Vertices are not shared between quads (4 x 12 bytes a quad): Embree
//    copies them into its BVH leaves anyway.
//  - build_seconds(): face extraction from the model + Embree's BVH build.
#pragma once
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/vec3.hpp>

#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/embree/device.hpp"
#include "voxray/embree/exposure.hpp"
#include "voxray/embree/trace.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::embree {

class quad_scene {
public:
    explicit quad_scene(const voxel_model& model, device dev = device()) : dev_(std::move(dev)) {
        auto start = std::chrono::steady_clock::now();
        for_each_voxel_exposure(model, [&](glm::ivec3 p, std::uint8_t material, std::uint8_t exposed) {
            for (std::uint32_t f = 0; f < 6; ++f)
                if (exposed & (1u << f)) faces_.push_back({p, f | (std::uint32_t(material) << 8)});
        });
        faces_.shrink_to_fit();
        check_limit("quad_scene face count", faces_.size(), std::size_t(RTC_INVALID_GEOMETRY_ID) - 1);

        std::size_t before = dev_.allocated_bytes();
        scene_.reset(rtcNewScene(dev_.handle()));
        dev_.check("rtcNewScene");
        // CONTEXT_FILTER_FUNCTION lets a packet bring the boundary filter in its context.
        rtcSetSceneFlags(scene_.get(), RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
        rtcSetSceneBuildQuality(scene_.get(), RTC_BUILD_QUALITY_HIGH);
        if (!faces_.empty()) attach_quads();
        rtcCommitScene(scene_.get());
        dev_.check("rtcCommitScene");
        std::size_t after = dev_.allocated_bytes();
        embree_bytes_ = after > before ? after - before : 0;
        build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }

    void closest_hit(std::span<const ray> rays, std::span<hit> hits, unsigned threads = 0) const {
        check_spans(rays.size(), hits.size());
        for_each_packet(rays.size(), threads, [&](std::size_t first, unsigned count) {
            packet pk;
            context ctx(faces_.data());
            if (!prepare(rays.subspan(first, count), hits.subspan(first, count), pk, ctx)) return;
            rtcIntersect16(pk.valid, scene_.get(), &ctx.base, &pk.rayhit);
            for (unsigned i = 0; i < count; ++i) {
                if (!pk.valid[i]) continue;
                hit& h = hits[first + i];
                if (pk.rayhit.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) {
                    h = miss_record();
                    continue;
                }
                const face_record& f = faces_[pk.rayhit.hit.primID[i]];
                h.t = pk.t(i);
                h.voxel = f.voxel;
                h.normal = static_cast<voxray::face>(f.face_material & 0xFFu);
                h.material = f.face_material >> 8;
                h.steps = 0;
                h.status = VX_STATUS_HIT;
            }
        });
    }

    void any_hit(std::span<const ray> rays, std::span<hit> hits, unsigned threads = 0) const {
        check_spans(rays.size(), hits.size());
        for_each_packet(rays.size(), threads, [&](std::size_t first, unsigned count) {
            packet pk;
            context ctx(faces_.data());
            if (!prepare(rays.subspan(first, count), hits.subspan(first, count), pk, ctx)) return;
            rtcOccluded16(pk.valid, scene_.get(), &ctx.base, &pk.rayhit.ray);
            for (unsigned i = 0; i < count; ++i) {
                if (!pk.valid[i]) continue;
                hit& h = hits[first + i];
                h = miss_record();
                // Embree's occlusion convention: tfar = -inf once an occluder is found.
                if (pk.rayhit.ray.tfar[i] == -std::numeric_limits<float>::infinity()) {
                    h.t = std::numeric_limits<float>::quiet_NaN();
                    h.status = VX_STATUS_HIT;
                }
            }
        });
    }

    std::size_t bytes() const { return embree_bytes_ + faces_.capacity() * sizeof(face_record); }
    std::size_t embree_bytes() const { return embree_bytes_; }
    double build_seconds() const { return build_seconds_; }
    std::size_t quad_count() const { return faces_.size(); }
    const device& embree_device() const { return dev_; }

private:
    struct face_record {
        glm::ivec3 voxel;
        std::uint32_t face_material;  // bits 0..7: VX_FACE_*, bits 8..15: palette index
    };

    struct context {
        RTCIntersectContext base;  // must stay first: the filter casts the pointer back
        const face_record* faces;
        explicit context(const face_record* f) : faces(f) { rtcInitIntersectContext(&base); }
    };

    void attach_quads() {
        RTCGeometry g = rtcNewGeometry(dev_.handle(), RTC_GEOMETRY_TYPE_QUAD);
        dev_.check("rtcNewGeometry(QUAD)");
        auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 4 * faces_.size()));
        auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
            g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), faces_.size()));
        dev_.check("rtcSetNewGeometryBuffer");
        for (std::size_t q = 0; q < faces_.size(); ++q) {
            const face_record& f = faces_[q];
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
        rtcAttachGeometry(scene_.get(), g);
        rtcReleaseGeometry(g);
        dev_.check("quad geometry setup");
    }

    // Loads a packet; lanes starting on a boundary plane are rebased and switch the packet's
    // filter on. Returns whether any lane is left to trace.
    bool prepare(std::span<const ray> rays, std::span<hit> hits, packet& pk, context& ctx) const {
        bool boundary = false;
        for (unsigned i = 0; i < packet_width; ++i) {
            if (i >= rays.size()) { pk.park(i); continue; }
            const ray& r = rays[i];
            if (!traceable(r)) { hits[i] = miss_record(); pk.park(i); continue; }
            glm::vec3 p = start_point(r);
            bool on_plane = on_boundary(p);
            boundary |= on_plane;
            pk.load(i, r, p, on_plane);
        }
        if (boundary) ctx.base.filter = &boundary_filter;
        return pk.any_valid();
    }

    static void boundary_filter(const RTCFilterFunctionNArguments* args) {
        const auto& ctx = *reinterpret_cast<const context*>(args->context);
        const unsigned N = args->N;
        for (unsigned i = 0; i < N; ++i) {
            if (!args->valid[i]) continue;
            const face_record& f = ctx.faces[RTCHitN_primID(args->hit, N, i)];
            int face = int(f.face_material & 0xFFu), a = face >> 1;
            float o[3] = {RTCRayN_org_x(args->ray, N, i), RTCRayN_org_y(args->ray, N, i), RTCRayN_org_z(args->ray, N, i)};
            float d[3] = {RTCRayN_dir_x(args->ray, N, i), RTCRayN_dir_y(args->ray, N, i), RTCRayN_dir_z(args->ray, N, i)};
            // Front face: moving against the outward normal (+a face entered moving -a).
            bool front = (face & 1) ? d[a] > 0.0f : d[a] < 0.0f;
            bool in_columns = true;
            for (int b = 0; b < 3; ++b)
                if (b != a && d[b] == 0.0f) {
                    float lo = float(f.voxel[b]);
                    in_columns &= o[b] >= lo && o[b] < lo + 1.0f;
                }
            if (!front || !in_columns) args->valid[i] = 0;
        }
    }

    device dev_;
    scene_handle scene_;
    std::vector<face_record> faces_;  // primitive id -> voxel, face, material
    std::size_t embree_bytes_ = 0;
    double build_seconds_ = 0.0;
};

}  // namespace voxray::embree
