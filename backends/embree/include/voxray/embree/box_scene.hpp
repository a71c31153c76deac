// Embree baseline 2: one user-geometry box per voxel, intersected by an exact slab test.
//
// Which voxels get a box: only those with at least one exposed face. A ray that starts
// outside the solid enters it through an exposed face, so enclosed voxels can never be its
// first hit; they matter only to a ray that *starts* inside one, and that case is answered
// before tracing by one lookup of the start voxel in a sorted set (voxel_set, 9 bytes per
// enclosed voxel) instead of a BVH leaf per voxel. A ray starting inside an exposed voxel is
// reported by that voxel's own callback (t = tmin, face inside). Results therefore match the
// reference for every ray, inside starts included.
//
// Per-lane data the callbacks need (the start voxel, counters, the occluder) travels in an
// extended RTCIntersectContext, found by the ray id that trace.hpp sets to the lane index.
//
// Results:
//  - closest_hit: the full contract. t is the slab entry (plane - o) / d in float; hits on
//    an equal t (an edge or corner) go to the lower face id (inside first), then the lower
//    primitive id, so the answer does not depend on Embree's traversal order. steps = the
//    number of slab tests the ray's callbacks ran (Embree does not expose its node visits).
//  - any_hit: status, plus the voxel that ended the search: t, voxel, face and material of
//    *a* solid voxel on the ray within [tmin, tmax], not necessarily the first.
//  - bytes(): Embree's allocations for this scene (BVH and geometry; measured by the
//    device's memory monitor across the build, so builds on a shared device must not run
//    concurrently) plus the primitive arrays (16 bytes a box) and the enclosed-voxel set.
//  - build_seconds(): exposure classification of the model + Embree's BVH build.
#pragma once
#include <chrono>
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
#include "voxray/embree/voxel_set.hpp"
#include "voxray/embree/voxel_slab.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::embree {

class box_scene {
public:
    explicit box_scene(const voxel_model& model, device dev = device()) : dev_(std::move(dev)) {
        auto start = std::chrono::steady_clock::now();
        bounds_ = model.bounds();
        check_limit("box_scene voxel count", model.voxel_count(), std::uint64_t(RTC_INVALID_GEOMETRY_ID) - 1);
        for_each_voxel_exposure(model, [&](glm::ivec3 p, std::uint8_t material, std::uint8_t exposed) {
            if (exposed) {
                boxes_.push_back({p, material});
            } else {
                interior_.add(p, material);
            }
        });
        interior_.finish();
        boxes_.shrink_to_fit();

        std::size_t before = dev_.allocated_bytes();
        scene_.reset(rtcNewScene(dev_.handle()));
        dev_.check("rtcNewScene");
        rtcSetSceneFlags(scene_.get(), RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(scene_.get(), RTC_BUILD_QUALITY_HIGH);
        if (!boxes_.empty()) {
            RTCGeometry g = rtcNewGeometry(dev_.handle(), RTC_GEOMETRY_TYPE_USER);
            dev_.check("rtcNewGeometry(USER)");
            rtcSetGeometryUserPrimitiveCount(g, unsigned(boxes_.size()));
            rtcSetGeometryUserData(g, boxes_.data());
            rtcSetGeometryBoundsFunction(g, &bounds_callback, nullptr);
            rtcSetGeometryIntersectFunction(g, &intersect_callback);
            rtcSetGeometryOccludedFunction(g, &occluded_callback);
            rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_HIGH);
            rtcCommitGeometry(g);
            rtcAttachGeometry(scene_.get(), g);
            rtcReleaseGeometry(g);
            dev_.check("box geometry setup");
        }
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
            context ctx;
            if (!prepare(rays.subspan(first, count), hits.subspan(first, count), pk, ctx)) return;
            rtcIntersect16(pk.valid, scene_.get(), &ctx.base, &pk.rayhit);
            for (unsigned i = 0; i < count; ++i) {
                if (!pk.valid[i]) continue;
                hit& h = hits[first + i];
                if (pk.rayhit.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) {
                    h = miss_record();
                    h.steps = ctx.steps[i];
                    continue;
                }
                const box& b = boxes_[pk.rayhit.hit.primID[i]];
                h = make_hit(pk.t(i), b, std::uint32_t(pk.rayhit.hit.u[i]), ctx.steps[i]);
            }
        });
    }

    void any_hit(std::span<const ray> rays, std::span<hit> hits, unsigned threads = 0) const {
        check_spans(rays.size(), hits.size());
        for_each_packet(rays.size(), threads, [&](std::size_t first, unsigned count) {
            packet pk;
            context ctx;
            if (!prepare(rays.subspan(first, count), hits.subspan(first, count), pk, ctx)) return;
            rtcOccluded16(pk.valid, scene_.get(), &ctx.base, &pk.rayhit.ray);
            for (unsigned i = 0; i < count; ++i) {
                if (!pk.valid[i]) continue;
                hit& h = hits[first + i];
                // Embree's occlusion convention: tfar = -inf once a hit is accepted.
                if (pk.rayhit.ray.tfar[i] != -std::numeric_limits<float>::infinity()) {
                    h = miss_record();
                    h.steps = ctx.steps[i];
                    continue;
                }
                h = make_hit(ctx.t[i] + pk.shift[i] + 0.0f, boxes_[ctx.prim[i]], ctx.face[i], ctx.steps[i]);
            }
        });
    }

    std::size_t bytes() const { return embree_bytes_ + boxes_.capacity() * sizeof(box) + interior_.bytes(); }
    std::size_t embree_bytes() const { return embree_bytes_; }
    double build_seconds() const { return build_seconds_; }
    std::size_t box_count() const { return boxes_.size(); }          // voxels with an exposed face
    std::size_t enclosed_count() const { return interior_.size(); }  // voxels found by lookup
    const device& embree_device() const { return dev_; }

private:
    struct box {
        glm::ivec3 voxel;
        std::uint32_t material;  // a full word keeps the record 16 bytes and aligned
    };

    // Extended intersect context: Embree hands it back to every callback unchanged. Lanes are
    // indexed by ray id (= lane in the packet).
    struct context {
        RTCIntersectContext base;  // must stay first: callbacks cast the pointer back
        glm::ivec3 start[packet_width];
        std::uint32_t steps[packet_width];
        // any_hit: what ended the search
        std::uint32_t prim[packet_width];
        float t[packet_width];
        std::uint32_t face[packet_width];
        context() { rtcInitIntersectContext(&base); }
    };

    // Loads a packet: contract misses and inside starts in enclosed voxels are answered here
    // (and parked), the rest go to Embree. Returns whether any lane is left to trace.
    bool prepare(std::span<const ray> rays, std::span<hit> hits, packet& pk, context& ctx) const {
        for (unsigned i = 0; i < packet_width; ++i) {
            ctx.steps[i] = 0;
            if (i >= rays.size()) { pk.park(i); continue; }
            const ray& r = rays[i];
            if (!traceable(r)) { hits[i] = miss_record(); pk.park(i); continue; }
            glm::vec3 p = start_point(r);
            glm::ivec3 s = voxel_at(p, bounds_);
            if (std::uint8_t m = interior_.find(s)) {
                hits[i] = make_hit(r.tmin, box{s, m}, VX_FACE_INSIDE, 0);
                pk.park(i);
                continue;
            }
            ctx.start[i] = s;
            pk.load(i, r, p, false);
        }
        return pk.any_valid();
    }

    static hit make_hit(float t, const box& b, std::uint32_t face, std::uint32_t steps) {
        hit h;
        h.t = t;
        h.voxel = b.voxel;
        h.normal = static_cast<voxray::face>(face);
        h.material = b.material;
        h.steps = steps;
        h.status = VX_STATUS_HIT;
        return h;
    }

    static void bounds_callback(const RTCBoundsFunctionArguments* args) {
        const box& b = static_cast<const box*>(args->geometryUserPtr)[args->primID];
        RTCBounds* out = args->bounds_o;
        out->lower_x = float(b.voxel.x);
        out->lower_y = float(b.voxel.y);
        out->lower_z = float(b.voxel.z);
        out->upper_x = float(b.voxel.x + 1);
        out->upper_y = float(b.voxel.y + 1);
        out->upper_z = float(b.voxel.z + 1);
    }

    // Reads lane i of an N-wide Embree ray and runs the slab test against voxel v.
    static voxel_entry test_lane(RTCRayN* ray, unsigned N, unsigned i, glm::ivec3 v, context& ctx,
                                 unsigned lane) {
        glm::vec3 o(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i));
        glm::vec3 d(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i));
        ++ctx.steps[lane];
        return enter_voxel(o, d, RTCRayN_tnear(ray, N, i), RTCRayN_tfar(ray, N, i), v, ctx.start[lane] == v);
    }

    // Ties at equal t: inside first, then the lower face id, then the lower primitive id.
    static std::uint32_t face_rank(std::uint32_t face) { return face == VX_FACE_INSIDE ? 0 : face + 1; }

    static void intersect_callback(const RTCIntersectFunctionNArguments* args) {
        auto& ctx = *reinterpret_cast<context*>(args->context);
        const box& b = static_cast<const box*>(args->geometryUserPtr)[args->primID];
        const unsigned N = args->N;
        RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, N);
        RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, N);
        for (unsigned i = 0; i < N; ++i) {
            if (!args->valid[i]) continue;
            unsigned lane = RTCRayN_id(ray, N, i);
            voxel_entry e = test_lane(ray, N, i, b.voxel, ctx, lane);
            if (!e.hit) continue;
            float& tfar = RTCRayN_tfar(ray, N, i);
            unsigned& geom = RTCHitN_geomID(hit, N, i);
            if (geom != RTC_INVALID_GEOMETRY_ID && e.t == tfar) {
                std::uint32_t rank = face_rank(e.face), old_rank = face_rank(std::uint32_t(RTCHitN_u(hit, N, i)));
                if (rank > old_rank || (rank == old_rank && args->primID > RTCHitN_primID(hit, N, i))) continue;
            }
            glm::vec3 n = face_normal(static_cast<voxray::face>(e.face));
            tfar = e.t;
            RTCHitN_Ng_x(hit, N, i) = n.x;
            RTCHitN_Ng_y(hit, N, i) = n.y;
            RTCHitN_Ng_z(hit, N, i) = n.z;
            RTCHitN_u(hit, N, i) = float(e.face);  // the entry face, read back by closest_hit
            RTCHitN_v(hit, N, i) = 0.0f;
            RTCHitN_primID(hit, N, i) = args->primID;
            geom = args->geomID;
            RTCHitN_instID(hit, N, i, 0) = ctx.base.instID[0];
        }
    }

    static void occluded_callback(const RTCOccludedFunctionNArguments* args) {
        auto& ctx = *reinterpret_cast<context*>(args->context);
        const box& b = static_cast<const box*>(args->geometryUserPtr)[args->primID];
        const unsigned N = args->N;
        for (unsigned i = 0; i < N; ++i) {
            if (!args->valid[i]) continue;
            unsigned lane = RTCRayN_id(args->ray, N, i);
            voxel_entry e = test_lane(args->ray, N, i, b.voxel, ctx, lane);
            if (!e.hit) continue;
            ctx.prim[lane] = args->primID;
            ctx.t[lane] = e.t;
            ctx.face[lane] = e.face;
            RTCRayN_tfar(args->ray, N, i) = -std::numeric_limits<float>::infinity();
        }
    }

    device dev_;
    scene_handle scene_;
    std::vector<box> boxes_;  // primitive id -> voxel, material
    voxel_set interior_;      // enclosed voxels, for inside starts
    box3i bounds_;
    std::size_t embree_bytes_ = 0;
    double build_seconds_ = 0.0;
};

}  // namespace voxray::embree
