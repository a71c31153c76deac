// Embree peer of voxray's scenes with entities (voxray/entities/): the world's exposed faces
// as quads in a scene of their own, each entity model's likewise, and in the top-level scene
// the world (no transform) and every instance as RTC_GEOMETRY_TYPE_INSTANCE of its model's
// scene with the pose's affine transform. move() sets a transform; commit() rebuilds Embree's
// top-level BVH over the instances (the world's and the models' BVHs stay). What
// `voxray bench SCENE.json` measures voxray's scenes against, on the same rays.
//
// Hits: the world's like quad_scene's; an instance's with its voxel and face in the model's
// own coordinates and the instance in the material's upper bits, as voxray's scenes report
// them (entities/scene_hit.hpp). Embree's t comes from its quad test (float rounding of the
// exact crossing, through a float transform), and this peer does not retrace back faces:
// it is a speed peer, compared by hit status only (rays that start inside solid excepted).
#pragma once
#include <algorithm>
#include <chrono>
#include <limits>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/mat3x3.hpp>

#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/embree/device.hpp"
#include "voxray/embree/face_quads.hpp"
#include "voxray/embree/trace.hpp"
#include "voxray/entities/layout.h"
#include "voxray/entities/pose.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::embree {

class instanced_scene {
public:
    static constexpr std::string_view name = "embree-instances";

    explicit instanced_scene(const voxel_model& world, device dev = device()) : dev_(std::move(dev)) {
        world_faces_ = exposed_faces(world);
        bounds_ = world.bounds();
        // The world's quads in a scene of their own, instanced once with no transform: a
        // frame's commit then rebuilds only the top level over the instances.
        world_.reset(rtcNewScene(dev_.handle()));
        rtcSetSceneFlags(world_.get(), RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(world_.get(), RTC_BUILD_QUALITY_HIGH);
        if (!world_faces_.empty()) attach_face_quads(dev_, world_.get(), world_faces_);
        rtcCommitScene(world_.get());
        top_.reset(rtcNewScene(dev_.handle()));
        dev_.check("rtcNewScene");
        rtcSetSceneFlags(top_.get(), RTC_SCENE_FLAG_ROBUST);
        RTCGeometry g = rtcNewGeometry(dev_.handle(), RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(g, world_.get());
        rtcSetGeometryTimeStepCount(g, 1);
        const float identity[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
        rtcSetGeometryTransform(g, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, identity);
        rtcCommitGeometry(g);
        world_geometry_ = rtcAttachGeometry(top_.get(), g);
        rtcReleaseGeometry(g);
        dev_.check("world instance");
    }

    std::uint32_t add_model(const voxel_model& m) {
        model_entry e;
        e.faces = exposed_faces(m);
        e.bounds = m.bounds();
        e.scene.reset(rtcNewScene(dev_.handle()));
        rtcSetSceneFlags(e.scene.get(), RTC_SCENE_FLAG_ROBUST);
        rtcSetSceneBuildQuality(e.scene.get(), RTC_BUILD_QUALITY_HIGH);
        if (!e.faces.empty()) attach_face_quads(dev_, e.scene.get(), e.faces);
        rtcCommitScene(e.scene.get());
        dev_.check("model scene");
        models_.push_back(std::move(e));
        return std::uint32_t(models_.size() - 1);
    }

    // An instance of `model` at pose p; its id counts from 0 in the order of add().
    std::uint32_t add(std::uint32_t model, const pose& p) {
        RTCGeometry g = rtcNewGeometry(dev_.handle(), RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(g, models_.at(model).scene.get());
        rtcSetGeometryTimeStepCount(g, 1);
        instances_.push_back({model, g});
        set_transform(std::uint32_t(instances_.size() - 1), p);
        unsigned geometry = rtcAttachGeometry(top_.get(), g);
        rtcReleaseGeometry(g);
        dev_.check("instance geometry");
        instance_of_geometry_.resize(std::max<std::size_t>(instance_of_geometry_.size(), geometry + 1), none);
        instance_of_geometry_[geometry] = std::uint32_t(instances_.size() - 1);
        return std::uint32_t(instances_.size() - 1);
    }

    void move(std::uint32_t id, const pose& p) { set_transform(id, p); }

    // Makes adds and moves take effect: the top-level BVH is rebuilt over the instances.
    void commit() {
        auto start = std::chrono::steady_clock::now();
        rtcCommitScene(top_.get());
        dev_.check("rtcCommitScene");
        commit_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    double commit_seconds() const { return commit_seconds_; }

    void closest_hit(std::span<const ray> rays, std::span<hit> hits, const trace_options& opt = {}) const {
        trace(rays, hits, opt, true);
    }
    void any_hit(std::span<const ray> rays, std::span<hit> hits, const trace_options& opt = {}) const {
        trace(rays, hits, opt, false);
    }

private:
    static constexpr std::uint32_t none = 0xFFFFFFFFu;
    struct model_entry {
        std::vector<face_quad> faces;
        box3i bounds;
        scene_handle scene;
    };
    struct instance_entry {
        std::uint32_t model;
        RTCGeometry geometry;  // owned by the top-level scene
    };

    // Model voxel m lands at  P + M (m - min - C)  in the world (entities/layout.h: M is the
    // rotation times scale, C the centre of the model's box from its min corner).
    void set_transform(std::uint32_t id, const pose& p) {
        const model_entry& m = models_[instances_[id].model];
        glm::dmat3 M = model_to_world(p);
        glm::dvec3 pivot = glm::dvec3(m.bounds.min) + glm::dvec3(m.bounds.extent()) * 0.5;
        glm::dvec3 t = glm::dvec3(p.position) - M * pivot;
        float xfm[12];  // column-major 3x4: three columns of M, then the translation
        for (int c = 0; c < 3; ++c)
            for (int r = 0; r < 3; ++r) xfm[3 * c + r] = float(M[c][r]);
        for (int r = 0; r < 3; ++r) xfm[9 + r] = float(t[r]);
        rtcSetGeometryTransform(instances_[id].geometry, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, xfm);
        rtcCommitGeometry(instances_[id].geometry);
    }

    void trace(std::span<const ray> rays, std::span<hit> hits, const trace_options& opt, bool closest) const {
        check_spans(rays.size(), hits.size());
        box3i everywhere{glm::ivec3(-(1 << 30)), glm::ivec3(1 << 30)};
        for_each_packet(rays.size(), opt.threads, [&](std::size_t first, unsigned count) {
            packet pk;
            RTCIntersectContext ctx;
            init_context(ctx, opt);
            for (unsigned i = 0; i < packet_width; ++i) {
                if (i >= count || !traceable(rays[first + i])) {
                    if (i < count) hits[first + i] = miss_record();
                    pk.park(i);
                    continue;
                }
                const ray& r = rays[first + i];
                if (!pk.load(i, r, start_point(r), false, everywhere)) hits[first + i] = miss_record();
                pk.rayhit.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
            }
            if (!pk.any_valid()) return;
            // Any-hit too: rtcOccluded16 did not return on shadow rays through instances here
            // (Embree 3.13.5, Debian: seen spinning for minutes on 2,304 rays), so any hit is
            // answered by the closest one, at its cost.
            rtcIntersect16(pk.valid, top_.get(), &ctx, &pk.rayhit);
            for (unsigned i = 0; i < count; ++i) {
                if (!pk.valid[i]) continue;
                hit& h = hits[first + i];
                h = miss_record();
                if (pk.rayhit.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) continue;
                if (!closest) {  // as quad_scene answers any hits: a status, t unknown
                    h.t = std::numeric_limits<float>::quiet_NaN();
                    h.status = VX_STATUS_HIT;
                    continue;
                }
                unsigned inst = pk.rayhit.hit.instID[0][i];
                std::uint32_t id = inst == world_geometry_ ? none : instance_of_geometry_[inst];
                const face_quad& f = id == none ? world_faces_[pk.rayhit.hit.primID[i]]
                                                : models_[instances_[id].model].faces[pk.rayhit.hit.primID[i]];
                h.t = pk.t(i);
                h.voxel = f.voxel;
                h.normal = static_cast<voxray::face>(f.face_material & 0xFFu);
                h.material = (f.face_material >> 8) | (id == none ? 0u : (id + 1) << VX_SC_INSTANCE_SHIFT);
                h.status = VX_STATUS_HIT;
            }
        });
    }

    device dev_;
    scene_handle world_, top_;
    unsigned world_geometry_ = 0;  // the world's instance in the top-level scene
    std::vector<face_quad> world_faces_;
    box3i bounds_;
    std::vector<model_entry> models_;
    std::vector<instance_entry> instances_;
    std::vector<std::uint32_t> instance_of_geometry_;  // top-level geometry id -> instance id
    double commit_seconds_ = 0;
};

}  // namespace voxray::embree
