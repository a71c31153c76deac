// Embree baseline 2: one user-geometry box per voxel, intersected by an exact slab test
// (voxel_slab.hpp). Matches the reference for every ray, inside starts included.
//
// Which voxels get a box: only those touching empty space through a face, an edge or a
// corner (one of their 26 neighbours is empty). The first solid voxel a ray from outside
// enters (over a non-zero length) is entered from the empty voxel the ray was in just
// before, one of its 26 neighbours; so fully enclosed voxels can never be a first hit.
// Faces alone are not enough: a ray through an edge or corner can enter a voxel whose 6 face
// neighbours are solid, touching those only at a point, which Embree's culling and float
// slab tests may or may not count.
//
// What is answered before tracing, because Embree cannot be relied on for it (measured: a
// ray that starts on a voxel's corner and leaves it at once touches the box only at
// t = tnear, and Embree's node culling drops such boxes):
//  - Inside starts: one lookup of the start voxel in a sorted set of all solid voxels
//    (voxel_set, 9 bytes a voxel, far less than a BVH leaf).
//  - A start on a boundary plane that enters a solid voxel right there (t = tmin) through
//    a face, edge or corner of its empty start voxel: such rays are rebased (so the plane
//    through the start has t = 0 exactly) and tested against the up to 8 voxels touching
//    the start point.
//
// Embree's culling is also inexact at tfar (trace.hpp, widen()): each lane's exact bound
// (tmax, then the best hit so far) is kept in the context and compared by the callbacks,
// while Embree gets a slightly wider tfar so that it still visits boxes entered exactly
// there. That makes hits at t == tmax exact. Per-lane data (bounds, counters, the
// occluder) travels in an extended RTCIntersectContext, found by the ray id that trace.hpp
// sets to the lane index.
//
// Results:
//  - closest_hit: the full contract. t is the slab entry (plane - o) / d in float. Among
//    boxes entered at an equal t (an edge or corner) the lower face id wins (inside
//    first), then the lower primitive id. Boxes that a ray only grazes at one point may or
//    may not be visited depending on Embree's traversal, so on such exact ties the voxel
//    reported can change with the coherence hint (measured: 1 ray in 5000 with 20% of
//    origins on integer coordinates). steps = slab tests run for the ray (Embree does not
//    expose its node visits).
//  - any_hit: status, plus the voxel that ended the search: t, voxel, face and material of
//    *a* solid voxel on the ray within [tmin, tmax], not necessarily the first.
//  - bytes(): Embree's allocations for this scene (BVH and geometry; measured by the
//    device's memory monitor across the build, so builds on a shared device must not run
//    concurrently) plus the primitive array (16 bytes a box) and the voxel set (9 bytes a
//    solid voxel).
//  - build_seconds(): exposure classification of the model + Embree's BVH build.
#pragma once
#include <chrono>
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
#include "voxray/embree/trace.hpp"
#include "voxray/embree/voxel_set.hpp"
#include "voxray/embree/voxel_slab.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::embree {

class box_scene {
public:
    static constexpr std::string_view name = "embree-boxes";
    static constexpr std::string_view library = "embree";
    explicit box_scene(const voxel_model& model, device dev = device()) : dev_(std::move(dev)) {
        auto start = std::chrono::steady_clock::now();
        bounds_ = model.bounds();
        check_limit("box_scene voxel count", model.voxel_count(), std::uint64_t(RTC_INVALID_GEOMETRY_ID) - 1);
        solid_.reserve(model.voxel_count());
        for_each_voxel_exposure(model, [&](glm::ivec3 p, std::uint8_t material, std::uint8_t exposed) {
            if (exposed) boxes_.push_back({p, material});
            solid_.add(p, material);
        }, true);
        solid_.finish();
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

    void closest_hit(std::span<const ray> rays, std::span<hit> hits, const trace_options& opt = {}) const {
        check_spans(rays.size(), hits.size());
        for_each_packet(rays.size(), opt.threads, [&](std::size_t first, unsigned count) {
            packet pk;
            context ctx(opt);
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
                // The exact bound is the hit's t (in Embree's frame).
                h = make_hit(pk.t(i, ctx.tfar[i]), b, std::uint32_t(pk.rayhit.hit.u[i]), ctx.steps[i]);
            }
        });
    }

    void any_hit(std::span<const ray> rays, std::span<hit> hits, const trace_options& opt = {}) const {
        check_spans(rays.size(), hits.size());
        for_each_packet(rays.size(), opt.threads, [&](std::size_t first, unsigned count) {
            packet pk;
            context ctx(opt);
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
                h = make_hit(pk.t(i, ctx.t[i]), boxes_[ctx.prim[i]], ctx.face[i], ctx.steps[i]);
            }
        });
    }

    std::size_t bytes() const { return embree_bytes_ + boxes_.capacity() * sizeof(box) + solid_.bytes(); }
    std::size_t embree_bytes() const { return embree_bytes_; }
    double build_seconds() const { return build_seconds_; }
    std::size_t box_count() const { return boxes_.size(); }  // voxels touching empty space
    std::size_t enclosed_count() const { return solid_.size() - boxes_.size(); }  // without a box
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
        float tfar[packet_width];  // exact bound: tmax, then the closest hit's t
        std::uint32_t steps[packet_width];
        // any_hit: what ended the search
        std::uint32_t prim[packet_width];
        float t[packet_width];
        std::uint32_t face[packet_width];
        explicit context(const trace_options& opt) { init_context(base, opt); }
    };

    // Loads a packet: contract misses and inside starts are answered here (and parked), the
    // rest go to Embree. Returns whether any lane is left to trace.
    bool prepare(std::span<const ray> rays, std::span<hit> hits, packet& pk, context& ctx) const {
        for (unsigned i = 0; i < packet_width; ++i) {
            ctx.steps[i] = 0;
            if (i >= rays.size()) { pk.park(i); continue; }
            const ray& r = rays[i];
            if (!traceable(r)) { hits[i] = miss_record(); pk.park(i); continue; }
            glm::vec3 p = start_point(r);
            glm::ivec3 s = voxel_at(p, bounds_);
            if (std::uint8_t m = solid_.find(s)) {
                hits[i] = make_hit(r.tmin, box{s, m}, VX_FACE_INSIDE, 0);
                pk.park(i);
                continue;
            }
            bool on_plane = starts_on_plane(p, r.direction);
            if (!pk.load(i, r, p, on_plane, bounds_)) {
                hits[i] = miss_record();
                continue;
            }
            ctx.tfar[i] = pk.rayhit.ray.tfar[i];
            if (on_plane && entry_at_start(pk, i, r.tmin, hits[i])) {
                pk.park(i);
                continue;
            }
            pk.rayhit.ray.tfar[i] = widen(ctx.tfar[i]);
        }
        return pk.any_valid();
    }

    // For a rebased lane starting on a boundary plane: whether the ray enters one of the solid
    // voxels touching its start point at once (t = 0 in Embree's frame). Ties (a start on an
    // edge or corner) go to the lower face id, then the lower voxel key.
    bool entry_at_start(const packet& pk, unsigned i, float tmin, hit& out) const {
        const RTCRay16& r = pk.rayhit.ray;
        glm::vec3 o(r.org_x[i], r.org_y[i], r.org_z[i]), d(r.dir_x[i], r.dir_y[i], r.dir_z[i]);
        for (int a = 0; a < 3; ++a)  // far from the model: nothing to touch (and no int overflow)
            if (!(o[a] >= float(bounds_.min[a] - 1) && o[a] <= float(bounds_.max[a]))) return false;
        glm::ivec3 base(glm::floor(o));
        int options[3];  // per axis: also the voxel below a plane that the ray crosses
        for (int a = 0; a < 3; ++a) options[a] = (d[a] != 0.0f && o[a] == float(base[a])) ? 2 : 1;
        bool found = false;
        std::uint32_t best_rank = 0, steps = 0;
        std::uint64_t best_key = 0;
        for (int z = 0; z < options[2]; ++z)
            for (int y = 0; y < options[1]; ++y)
                for (int x = 0; x < options[0]; ++x) {
                    glm::ivec3 v = base - glm::ivec3(x, y, z);
                    std::uint8_t m = solid_.find(v);
                    if (!m) continue;
                    ++steps;
                    voxel_entry e = enter_voxel(o, d, 0.0f, r.tfar[i], v);
                    if (!e.hit) continue;  // the ray leaves v here
                    std::uint32_t rank = face_rank(e.face);
                    std::uint64_t key = voxel_set::key(v);
                    if (found && (rank > best_rank || (rank == best_rank && key > best_key))) continue;
                    found = true;
                    best_rank = rank;
                    best_key = key;
                    out = make_hit(tmin, box{v, m}, e.face, steps);
                }
        if (found) out.steps = steps;
        return found;
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

    // Reads lane i of an N-wide Embree ray and runs the slab test against voxel v. Inside
    // starts never get here (prepare() answered them).
    static voxel_entry test_lane(RTCRayN* ray, unsigned N, unsigned i, glm::ivec3 v, context& ctx,
                                 unsigned lane) {
        glm::vec3 o(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i));
        glm::vec3 d(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i));
        ++ctx.steps[lane];
        return enter_voxel(o, d, RTCRayN_tnear(ray, N, i), ctx.tfar[lane], v);
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
            unsigned& geom = RTCHitN_geomID(hit, N, i);
            if (geom != RTC_INVALID_GEOMETRY_ID && e.t == ctx.tfar[lane]) {
                std::uint32_t rank = face_rank(e.face), old_rank = face_rank(std::uint32_t(RTCHitN_u(hit, N, i)));
                if (rank > old_rank || (rank == old_rank && args->primID > RTCHitN_primID(hit, N, i))) continue;
            }
            glm::vec3 n = face_normal(static_cast<voxray::face>(e.face));
            ctx.tfar[lane] = e.t;
            RTCRayN_tfar(ray, N, i) = widen(e.t);
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
    voxel_set solid_;         // every solid voxel, for inside starts
    box3i bounds_;
    std::size_t embree_bytes_ = 0;
    double build_seconds_ = 0.0;
};

}  // namespace voxray::embree
