// NanoVDB baseline: the model's voxels as active values (the palette index) of a NanoVDB
// uint32 grid in index space (voxel size 1, so grid coordinates are world voxels), traced
// on the CPU by a hierarchical DDA over NanoVDB's tree.
//
// Why a loop of our own: nanovdb::firstActive jumps ahead by a fixed step and is not
// voxel-exact, and nanovdb::HDDA re-derives the cell from a float point after every level
// change (RoundDown(ray(t))), which can land one voxel off next to a boundary. Here the
// walk keeps the current voxel as integers: at each cell it asks NanoVDB
//   isActive(v)   — a solid voxel (or an active tile): the hit;
//   getDim(v)     — the size of the empty node or tile holding v (1 inside a leaf);
// then leaves that whole node through the nearest of its faces, in double. Axes that
// reach their face at the same t step together, like the reference DDA; on the other axes
// the new voxel is the floor of the exit point clamped into the node, so at the voxel
// level the walk is exact integer stepping.
//
// Contract (as the reference, voxray/kernels/dda.h): rays with NaN/Inf, a zero direction
// (components below 2^-120 count as zero) or tmin > tmax miss; a ray starting inside a
// solid voxel hits it with face inside at t = tmin; steps counts cells visited.
// any_hit returns status only (t = NaN on a hit).
#pragma once
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <span>
#include <string_view>
#include <thread>
#include <vector>

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridBuilder.h>
#include <nanovdb/util/Ray.h>

#include "voxray/core/error.hpp"
#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::vdb {

class hdda_scene {
public:
    static constexpr std::string_view name = "nanovdb-hdda";
    static constexpr std::string_view library = "nanovdb";

    explicit hdda_scene(const voxel_model& model) {
        auto start = std::chrono::steady_clock::now();
        nanovdb::GridBuilder<std::uint32_t> builder(0u);
        auto acc = builder.getAccessor();
        model.for_each_voxel([&](glm::ivec3 p, std::uint8_t v) { acc.setValue(nanovdb::Coord(p.x, p.y, p.z), v); });
        handle_ = builder.getHandle<>(1.0, nanovdb::Vec3d(0.0), "voxray");
        grid_ = handle_.grid<std::uint32_t>();
        if (!grid_) fail("nanovdb baseline: the grid builder returned no uint32 grid");
        empty_ = model.voxel_count() == 0;
        auto bb = grid_->indexBBox();
        lo_ = glm::dvec3(bb.min()[0], bb.min()[1], bb.min()[2]);
        hi_ = glm::dvec3(bb.max()[0], bb.max()[1], bb.max()[2]) + 1.0;
        build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }

    std::size_t bytes() const { return std::size_t(handle_.size()); }
    double build_seconds() const { return build_seconds_; }
    unsigned threads() const { return std::max(1u, std::thread::hardware_concurrency()); }

    void closest_hit(std::span<const ray> rays, std::span<hit> hits) const { trace(rays, hits, false); }
    void any_hit(std::span<const ray> rays, std::span<hit> hits) const { trace(rays, hits, true); }

private:
    using accessor = decltype(std::declval<const nanovdb::NanoGrid<std::uint32_t>&>().getAccessor());

    void trace(std::span<const ray> rays, std::span<hit> hits, bool any) const {
        if (rays.size() != hits.size()) fail("nanovdb trace: ", rays.size(), " rays but room for ", hits.size(), " hits");
        constexpr std::size_t batch = 1024;
        std::atomic<std::size_t> next{0};
        auto work = [&] {
            auto acc = grid_->getAccessor();  // one accessor (node cache) per thread
            for (std::size_t b; (b = next.fetch_add(batch)) < rays.size();)
                for (std::size_t i = b; i < std::min(rays.size(), b + batch); ++i) {
                    hits[i] = walk(rays[i], acc);
                    if (any && hits[i].is_hit()) hits[i].t = std::numeric_limits<float>::quiet_NaN();
                }
        };
        std::vector<std::thread> pool;
        for (unsigned k = 1; k < threads() && k * batch < rays.size(); ++k) pool.emplace_back(work);
        work();
        for (auto& t : pool) t.join();
    }

    static bool moves(float d) { return std::abs(d) >= 7.52316385e-37f; }  // the reference's threshold

    hit walk(const ray& r, accessor& acc) const {
        hit h;
        glm::dvec3 o(r.origin), d(r.direction), inv(0.0);
        bool finite = std::isfinite(r.tmin) && !std::isnan(r.tmax);
        bool any_axis = false;
        for (int a = 0; a < 3; ++a) {
            finite = finite && std::isfinite(r.origin[a]) && std::isfinite(r.direction[a]);
            if (moves(r.direction[a])) inv[a] = 1.0 / d[a], any_axis = true;
            else d[a] = 0.0;
        }
        if (!finite || !any_axis || !(r.tmin <= r.tmax) || empty_) return h;

        // Clip to the grid's active box; remember the axis the ray enters it through.
        double t0 = r.tmin, t1 = r.tmax;
        int entry_axis = -1;
        for (int a = 0; a < 3; ++a) {
            if (d[a] == 0.0) {
                if (o[a] < lo_[a] || o[a] >= hi_[a]) return h;
                continue;
            }
            double ta = (lo_[a] - o[a]) * inv[a], tb = (hi_[a] - o[a]) * inv[a];
            double near = std::min(ta, tb);
            if (near > t0) t0 = near, entry_axis = a;
            t1 = std::min(t1, std::max(ta, tb));
        }
        if (!(t0 <= t1)) return h;

        nanovdb::Coord v;
        for (int a = 0; a < 3; ++a) {
            double p = std::clamp(std::floor(o[a] + t0 * d[a]), lo_[a], hi_[a] - 1.0);
            v[a] = int(p);
        }
        face entered = face::inside;
        if (entry_axis >= 0) {
            v[entry_axis] = d[entry_axis] > 0 ? int(lo_[entry_axis]) : int(hi_[entry_axis]) - 1;
            entered = entry_face(entry_axis, d[entry_axis]);
        }
        nanovdb::Ray<float> unused;  // getDim's ray argument (NanoVDB ignores it on the CPU)
        double t = t0;
        for (std::uint32_t steps = 1;; ++steps) {
            if (acc.isActive(v)) {
                h.t = float(t);
                h.voxel = {v[0], v[1], v[2]};
                h.normal = entered;
                h.material = acc.getValue(v);
                h.steps = steps;
                h.status = VX_STATUS_HIT;
                return h;
            }
            int dim = int(acc.getDim(v, unused));
            glm::dvec3 exit(std::numeric_limits<double>::infinity());
            nanovdb::Coord node_min = v & ~(dim - 1);
            for (int a = 0; a < 3; ++a)
                if (d[a] != 0.0) exit[a] = (double(d[a] > 0 ? node_min[a] + dim : node_min[a]) - o[a]) * inv[a];
            double tn = std::min({exit.x, exit.y, exit.z});
            if (!(tn <= t1)) {
                h.steps = steps;
                return h;
            }
            for (int a = 0; a < 3; ++a) {
                if (exit[a] == tn) {
                    v[a] = d[a] > 0 ? node_min[a] + dim : node_min[a] - 1;
                    entered = entry_face(a, d[a]);
                } else if (dim > 1) {
                    double p = std::floor(o[a] + tn * d[a]);
                    v[a] = int(std::clamp(p, double(node_min[a]), double(node_min[a] + dim - 1)));
                }
            }
            t = tn;
        }
    }

    static face entry_face(int axis, double d) {
        static constexpr face pos[3] = {face::neg_x, face::neg_y, face::neg_z};  // moving +a enters through -a
        static constexpr face neg[3] = {face::pos_x, face::pos_y, face::pos_z};
        return d > 0 ? pos[axis] : neg[axis];
    }

    nanovdb::GridHandle<nanovdb::HostBuffer> handle_;
    const nanovdb::NanoGrid<std::uint32_t>* grid_ = nullptr;
    glm::dvec3 lo_{0.0}, hi_{0.0};
    bool empty_ = true;
    double build_seconds_ = 0.0;
};

}  // namespace voxray::vdb
