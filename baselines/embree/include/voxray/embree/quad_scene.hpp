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
// Degenerate cases that would otherwise differ from the reference DDA:
//  - A ray running exactly along a plane x = k (zero x direction) belongs to voxel column k
//    (voxel x covers [x, x+1)), but Embree's watertight test would also hit the quads of
//    column k-1 on their edge. trace.hpp moves such an origin to the middle of column k.
//  - Back-face hits. A ray from outside solid enters voxels through front faces only, but
//    Embree also reports back faces: a ray that starts on a solid voxel's face and leaves it
//    hits that face at t = tnear, and a ray through an edge or corner may hit the face it
//    leaves by at the same t as one it enters by. A context filter that rejects back faces
//    fixes both, but costs about 20% when always on (measured on coherent rays), so:
//    - closest_hit traces unfiltered, then retraces with the filter only the lanes whose
//      hit is a back face (rare: starts on a surface, rays through edges);
//    - any_hit, which cannot see which face stopped it, traces with the filter every packet
//      holding a ray that starts on a boundary plane (shadow rays leaving a surface).
//    Rays starting on a boundary plane they cross are also rebased to start at tnear 0, so
//    that plane's t is exactly 0 and a front face there is not lost to rounding below tnear.
//  - A hit exactly at tmax: closest_hit gives Embree a slightly wider tfar (widen()) and
//    discards hits beyond the exact one. any_hit does not (a shadow ray touching an occluder
//    exactly at tmax may count either way).
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
#include <string_view>
#include <limits>
#include <span>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/vec3.hpp>

#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/embree/device.hpp"
#include "voxray/embree/exposure.hpp"
#include "voxray/embree/face_quads.hpp"
#include "voxray/embree/trace.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::embree {

class quad_scene {
public:
    static constexpr std::string_view name = "embree-quads";
    static constexpr std::string_view library = "embree";
    // What bench and check label instead of counting as mismatches (see LIMITATION above).
    static constexpr std::string_view limitation = "rays that start inside solid see only the inner side of surface quads";
    explicit quad_scene(const voxel_model& model, device dev = device()) : dev_(std::move(dev)) {
        auto start = std::chrono::steady_clock::now();
        bounds_ = model.bounds();
        faces_ = exposed_faces(model);

        std::size_t before = dev_.allocated_bytes();
        scene_.reset(rtcNewScene(dev_.handle()));
        dev_.check("rtcNewScene");
        // CONTEXT_FILTER_FUNCTION lets a packet bring the boundary filter in its context.
        rtcSetSceneFlags(scene_.get(), RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION);
        rtcSetSceneBuildQuality(scene_.get(), RTC_BUILD_QUALITY_HIGH);
        if (!faces_.empty()) attach_face_quads(dev_, scene_.get(), faces_);
        rtcCommitScene(scene_.get());
        dev_.check("rtcCommitScene");
        std::size_t after = dev_.allocated_bytes();
        embree_bytes_ = after > before ? after - before : 0;
        build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }

    void closest_hit(std::span<const ray> rays, std::span<hit> hits, const trace_options& opt = {}) const {
        check_spans(rays.size(), hits.size());
        for_each_packet(rays.size(), opt.threads, [&](std::size_t first, unsigned count) {
            packet pk;
            context ctx(faces_.data(), opt);
            if (!prepare(rays.subspan(first, count), hits.subspan(first, count), pk)) return;
            float tfar[packet_width];
            for (unsigned i = 0; i < packet_width; ++i) {
                tfar[i] = pk.rayhit.ray.tfar[i];
                pk.rayhit.ray.tfar[i] = widen(tfar[i]);
            }
            rtcIntersect16(pk.valid, scene_.get(), &ctx.base, &pk.rayhit);
            retrace_back_faces(pk, ctx, tfar);
            for (unsigned i = 0; i < count; ++i) {
                if (!pk.valid[i]) continue;
                hit& h = hits[first + i];
                // Embree finds the closest hit within the widened bound, so if even that one
                // lies beyond the exact bound, nothing lies within it.
                if (pk.rayhit.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID || pk.rayhit.ray.tfar[i] > tfar[i]) {
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

    void any_hit(std::span<const ray> rays, std::span<hit> hits, const trace_options& opt = {}) const {
        check_spans(rays.size(), hits.size());
        for_each_packet(rays.size(), opt.threads, [&](std::size_t first, unsigned count) {
            packet pk;
            context ctx(faces_.data(), opt);
            if (!prepare(rays.subspan(first, count), hits.subspan(first, count), pk)) return;
            if (pk.boundary) ctx.base.filter = &front_face_filter;
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
    using face_record = face_quad;

    struct context {
        RTCIntersectContext base;  // must stay first: the filter casts the pointer back
        const face_record* faces;
        context(const face_record* f, const trace_options& opt) : faces(f) { init_context(base, opt); }
    };

    // Loads a packet; lanes starting on a boundary plane are rebased. Returns whether any
    // lane is left to trace.
    bool prepare(std::span<const ray> rays, std::span<hit> hits, packet& pk) const {
        pk.boundary = false;
        for (unsigned i = 0; i < packet_width; ++i) {
            if (i >= rays.size()) { pk.park(i); continue; }
            const ray& r = rays[i];
            if (!traceable(r)) { hits[i] = miss_record(); pk.park(i); continue; }
            glm::vec3 p = start_point(r);
            bool on_plane = starts_on_plane(p, r.direction);
            pk.boundary |= on_plane;
            if (!pk.load(i, r, p, on_plane, bounds_)) hits[i] = miss_record();
        }
        return pk.any_valid();
    }

    // Front face: the ray moves against the face's outward normal (a +x face is entered
    // moving -x). d_axis is the ray's direction along the face's axis.
    static bool front_facing(const face_record& f, float d_axis) {
        return (f.face_material & 1u) ? d_axis > 0.0f : d_axis < 0.0f;
    }
    static float direction_on_axis(const RTCRay16& r, unsigned i, const face_record& f) {
        int a = int(f.face_material & 0xFFu) >> 1;
        return a == 0 ? r.dir_x[i] : a == 1 ? r.dir_y[i] : r.dir_z[i];
    }

    // Traces again, with the front-face filter, the lanes whose closest hit is a back face.
    // tfar: the exact bounds (Embree gets them widened again).
    void retrace_back_faces(packet& pk, context& ctx, const float* tfar) const {
        alignas(64) int again[packet_width];
        bool any = false;
        for (unsigned i = 0; i < packet_width; ++i) {
            again[i] = 0;
            if (!pk.valid[i] || pk.rayhit.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
            const face_record& f = faces_[pk.rayhit.hit.primID[i]];
            if (front_facing(f, direction_on_axis(pk.rayhit.ray, i, f))) continue;
            again[i] = -1;
            any = true;
            pk.rayhit.ray.tfar[i] = widen(tfar[i]);
            pk.rayhit.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        }
        if (!any) return;
        ctx.base.filter = &front_face_filter;
        rtcIntersect16(again, scene_.get(), &ctx.base, &pk.rayhit);
        ctx.base.filter = nullptr;
    }

    static void front_face_filter(const RTCFilterFunctionNArguments* args) {
        const auto& ctx = *reinterpret_cast<const context*>(args->context);
        const unsigned N = args->N;
        for (unsigned i = 0; i < N; ++i) {
            if (!args->valid[i]) continue;
            const face_record& f = ctx.faces[RTCHitN_primID(args->hit, N, i)];
            int a = int(f.face_material & 0xFFu) >> 1;
            float d = a == 0 ? RTCRayN_dir_x(args->ray, N, i)
                    : a == 1 ? RTCRayN_dir_y(args->ray, N, i)
                             : RTCRayN_dir_z(args->ray, N, i);
            if (!front_facing(f, d)) args->valid[i] = 0;
        }
    }

    device dev_;
    scene_handle scene_;
    std::vector<face_record> faces_;  // primitive id -> voxel, face, material
    box3i bounds_;
    std::size_t embree_bytes_ = 0;
    double build_seconds_ = 0.0;
};

}  // namespace voxray::embree
