// Packet tracing shared by the Embree scenes: the voxray ray contract (which rays are a
// miss without tracing), loading voxray rays into 16-wide Embree packets, and spreading the
// packets over threads.
//
// Details of Embree 3 that shape this file (all measured on Debian's build, which keeps
// Embree's asserts):
//  - Embree asserts tnear >= 0, while voxray allows a negative tmin. Such rays are
//    *rebased*: Embree sees origin o + tmin * d, tnear 0, tfar tmax - tmin, and tmin is
//    added back to the hit t. The scenes also rebase rays whose start point lies on a voxel
//    boundary (see quad_scene.hpp, box_scene.hpp).
//  - Embree asserts |origin|, |direction| <= 1.8e18; far rays are clipped (load_far).
//  - rtcIntersect16 needs its valid mask and packet 64-byte aligned.
//  - Embree's culling is not exact at the ends of the interval or along planes; see
//    widen() and packet::set_lane for what the scenes do about it.
#pragma once
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <initializer_list>
#include <limits>
#include <mutex>
#include <span>
#include <thread>
#include <vector>

#include <embree3/rtcore.h>
#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "voxray/core/box.hpp"
#include "voxray/core/error.hpp"
#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"

namespace voxray::embree {

inline constexpr unsigned packet_width = 16;

// How closest_hit / any_hit run.
struct trace_options {
    unsigned threads = 0;  // 0: all cores (std::thread::hardware_concurrency())
    // Embree's coherence hint. Coherent (camera rays, rays in tiles) lets Embree keep whole
    // packets together: about 3x faster on primary rays here (measured: quads 4.5 -> 13
    // Mrays/s, one thread). Set false for scattered rays (diffuse bounces).
    bool coherent = true;
};

// An intersect context with the coherence hint of `opt`.
inline void init_context(RTCIntersectContext& c, const trace_options& opt) {
    rtcInitIntersectContext(&c);
    c.flags = opt.coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
}

inline bool finite3(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The point at tmin, computed in one place so that every decision about where a ray starts
// (the inside lookup, the boundary test, the rebased origin) sees the same float value.
inline glm::vec3 start_point(const ray& r) {
    return r.tmin == 0.0f ? r.origin : r.origin + r.tmin * r.direction;
}

// A ray that is a miss by contract: NaN/Inf in origin, direction or tmin, NaN tmax, a zero
// direction, or an empty interval (tmin > tmax). tmax = +inf is allowed. A start point that
// overflows (a huge tmin) is treated the same way: it lies nowhere, and Embree must not see it.
inline bool traceable(const ray& r) {
    if (!finite3(r.origin) || !finite3(r.direction) || !std::isfinite(r.tmin) || std::isnan(r.tmax)) return false;
    if (r.direction.x == 0.0f && r.direction.y == 0.0f && r.direction.z == 0.0f) return false;
    return r.tmin <= r.tmax && finite3(start_point(r));
}

inline hit miss_record() { return hit{}; }  // t = +inf, face none, material 0, status miss

// floor and "is an integer" through int conversion: a build for baseline x86-64 (no SSE4.1)
// turns std::floor into a slow bit-twiddling sequence, which measured as a large part of the
// per-ray work here. floor_int needs |x| < 2^31; is_integer holds for any finite x.
inline int floor_int(float x) {
    int i = int(x);  // truncates toward zero
    return float(i) > x ? i - 1 : i;
}
inline bool is_integer(float x) { return !(std::abs(x) < 0x1p23f) || float(int(x)) == x; }

// The voxel containing point p (voxel x covers [x, x+1)), when p lies inside `bounds`;
// otherwise an impossible coordinate that matches no voxel. The float comparison comes first
// so a far-away point never overflows the int conversion.
inline glm::ivec3 voxel_at(glm::vec3 p, const box3i& bounds) {
    constexpr int nowhere = std::numeric_limits<int>::min();
    for (int a = 0; a < 3; ++a)
        if (!(p[a] >= float(bounds.min[a]) && p[a] < float(bounds.max[a]))) return glm::ivec3(nowhere);
    return {floor_int(p.x), floor_int(p.y), floor_int(p.z)};
}

// Whether the ray starts on a voxel boundary plane that it crosses: some coordinate of the
// start point p is an integer on an axis where the direction d is not zero.
inline bool starts_on_plane(glm::vec3 p, glm::vec3 d) {
    return (d.x != 0.0f && is_integer(p.x)) || (d.y != 0.0f && is_integer(p.y)) || (d.z != 0.0f && is_integer(p.z));
}

// A bound a little above t, for Embree's tfar. Embree's node culling computes box entries
// with an approximate reciprocal and drops a box entered exactly at tfar (measured: a hit
// at t == tmax is lost). The scenes give Embree this widened bound and keep the exact one
// themselves (box callbacks compare against it; quad hits beyond it are discarded).
inline float widen(float t) { return t + std::abs(t) * 0x1p-16f + 0x1p-100f; }

// One 16-ray packet as Embree wants it, plus per-lane bookkeeping. Embree traces each lane
// in its own frame; t = shift + scale * t_embree maps back to the caller's ray parameter.
struct packet {
    alignas(64) int valid[packet_width];
    alignas(64) RTCRayHit16 rayhit;
    double shift[packet_width];  // tmin for rebased lanes, the clip point for far rays, else 0
    double scale[packet_width];  // 1, or 1 / |d|max for far rays
    bool boundary = false;       // set by a scene when some lane starts on a boundary plane

    // Beyond this, an origin or direction component makes the ray "far" (see load_far).
    static constexpr float far = 0x1p40f;

    // Loads r into lane i; `rebase` moves the origin to `start` (= start_point(r)) and
    // traces from tnear 0. Rays with tmin < 0 are always rebased. Far rays are clipped to
    // `bounds` (the model's); returns false when such a ray cannot meet the model (a miss;
    // the lane is then parked). Both Embree geometry types ignore the ray's time, mask and
    // flags, which are set to neutral values.
    bool load(unsigned i, const ray& r, glm::vec3 start, bool rebase, const box3i& bounds) {
        rebase = rebase || r.tmin < 0.0f;
        glm::vec3 o = rebase ? start : r.origin;
        glm::vec3 ao = glm::abs(o), ad = glm::abs(r.direction);
        if (std::max({ao.x, ao.y, ao.z, ad.x, ad.y, ad.z}) > far) return load_far(i, r, bounds);
        set_lane(i, o, r.direction, rebase ? 0.0f : r.tmin, rebase ? r.tmax - r.tmin : r.tmax);
        shift[i] = rebase ? double(r.tmin) : 0.0;
        scale[i] = 1.0;
        return true;
    }

    // Marks lane i inactive and fills it with harmless values.
    void park(unsigned i) {
        set_lane(i, glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, 1.0f), 0.0f, 0.0f);
        rayhit.ray.mask[i] = 0;
        shift[i] = 0.0;
        scale[i] = 1.0;
        valid[i] = 0;
    }
    bool any_valid() const {
        for (unsigned i = 0; i < packet_width; ++i)
            if (valid[i]) return true;
        return false;
    }
    // The caller's ray parameter for an Embree-frame t of lane i. Adding +0.0f maps a -0
    // (Embree reports one for a hit exactly at tnear) to +0.
    float t(unsigned i, float t_embree) const { return float(shift[i] + scale[i] * double(t_embree)) + 0.0f; }
    float t(unsigned i) const { return t(i, rayhit.ray.tfar[i]); }

private:
    void set_lane(unsigned i, glm::vec3 o, glm::vec3 d, float tnear, float tfar) {
        // +0.0f turns -0 into +0, so "which side of a plane" never depends on a zero's sign.
        d += 0.0f;
        // Along an axis with zero direction the ray never leaves its row of voxels, and where
        // in the row it runs changes neither which voxels it meets nor any t. So move it to
        // the middle of its row (voxel y covers [y, y+1)). Measured reasons: with o on a
        // boundary plane, Embree's node test computes (plane - o) * (1 / 0) = NaN and culls
        // the boxes of the ray's own row; and its watertight quad test hits the faces of the
        // row below on their edge, even with o moved up by one ulp. Beyond 2^22 floats are
        // too coarse for this, but no voxel lies there (coordinates stay below 2^20).
        for (int a = 0; a < 3; ++a)
            if (d[a] == 0.0f && std::abs(o[a]) < 0x1p22f) o[a] = float(floor_int(o[a])) + 0.5f;
        RTCRay16& p = rayhit.ray;
        p.org_x[i] = o.x; p.org_y[i] = o.y; p.org_z[i] = o.z;
        p.dir_x[i] = d.x; p.dir_y[i] = d.y; p.dir_z[i] = d.z;
        p.tnear[i] = tnear;
        p.tfar[i] = tfar;
        p.time[i] = 0.0f;
        p.mask[i] = 0xFFFFFFFFu;
        p.id[i] = i;  // callbacks find per-lane data in their context by this id
        p.flags[i] = 0;
        rayhit.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        rayhit.hit.primID[i] = RTC_INVALID_GEOMETRY_ID;
        rayhit.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
        valid[i] = -1;
    }

    // A ray from very far away or with a huge direction. Embree asserts |org|, |dir| <=
    // 1.8e18 (its FLT_LARGE; Debian keeps the asserts), and such coordinates say nothing
    // about voxels anyway: the model lies within 2^20 of the origin. So clip the ray to the
    // model's bounds grown by one voxel, in double, and give Embree an equivalent tame ray:
    // origin at the clip point, direction scaled to a largest component of 1. When even
    // double cannot place the clip point near the model (an origin beyond ~2^70, where
    // double's spacing exceeds the model), the ray is reported as a miss.
    bool load_far(unsigned i, const ray& r, const box3i& bounds) {
        glm::dvec3 o(r.origin), d(r.direction);
        double t0 = r.tmin, t1 = r.tmax;
        for (int a = 0; a < 3; ++a) {
            double lo = bounds.min[a] - 1.0, hi = bounds.max[a] + 1.0;
            if (d[a] == 0.0) {
                if (o[a] < lo || o[a] > hi) t1 = -1.0, t0 = 0.0;  // never meets the box
                continue;
            }
            double ta = (lo - o[a]) / d[a], tb = (hi - o[a]) / d[a];
            t0 = std::max(t0, std::min(ta, tb));
            t1 = std::min(t1, std::max(ta, tb));
        }
        glm::dvec3 clip = o + t0 * d;
        double reach = std::max({std::abs(clip.x), std::abs(clip.y), std::abs(clip.z)});
        if (bounds.empty() || !(t0 <= t1) || !(reach < far)) {
            park(i);
            return false;
        }
        double dmax = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
        set_lane(i, glm::vec3(clip), glm::vec3(d / dmax), 0.0f, float((t1 - t0) * dmax));
        shift[i] = t0;
        scale[i] = 1.0 / dmax;
        return true;
    }
};

inline unsigned thread_count(unsigned requested) {
    if (requested) return requested;
    unsigned n = std::thread::hardware_concurrency();
    return n ? n : 1;
}

inline void check_spans(std::size_t rays, std::size_t hits) {
    if (rays != hits) fail("embree trace: ", rays, " rays but room for ", hits, " hits; the spans must match");
}

// Calls f(first, count) for every packet [first, first + count) of up to 16 of n rays, on up
// to `threads` threads (0: all cores). Threads take batches of packets from a shared counter
// so that slow regions of the scene do not leave a thread idle. The calling thread works
// too; small calls run on it alone, since starting a thread costs more than a few packets.
template <class F>
void for_each_packet(std::size_t n, unsigned threads, F&& f) {
    constexpr std::size_t batch = 16 * packet_width;  // rays taken at a time
    const std::size_t batches = (n + batch - 1) / batch;
    auto run_batch = [&](std::size_t b) {
        std::size_t end = std::min(n, (b + 1) * batch);
        for (std::size_t first = b * batch; first < end; first += packet_width)
            f(first, unsigned(std::min<std::size_t>(packet_width, end - first)));
    };
    std::size_t workers = std::min<std::size_t>(thread_count(threads), batches);
    if (workers <= 1) {
        for (std::size_t b = 0; b < batches; ++b) run_batch(b);
        return;
    }
    std::atomic<std::size_t> next{0};
    std::exception_ptr failure;
    std::mutex failure_mutex;
    auto work = [&] {
        try {
            for (std::size_t b; (b = next.fetch_add(1, std::memory_order_relaxed)) < batches;) run_batch(b);
        } catch (...) {
            std::lock_guard lock(failure_mutex);
            if (!failure) failure = std::current_exception();
            next.store(batches);  // stop the others early
        }
    };
    std::vector<std::thread> pool;
    pool.reserve(workers - 1);
    for (std::size_t i = 1; i < workers; ++i) pool.emplace_back(work);
    work();
    for (auto& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
}

}  // namespace voxray::embree
