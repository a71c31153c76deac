// Packet tracing shared by the Embree scenes: the voxray ray contract (which rays are a
// miss without tracing), loading voxray rays into 16-wide Embree packets, and spreading the
// packets over threads.
//
// Two details of Embree 3 shape this file:
//  - Embree asserts tnear >= 0 (the Debian build keeps its asserts), while voxray allows a
//    negative tmin. Such rays are *rebased*: Embree sees origin o + tmin * d, tnear 0,
//    tfar tmax - tmin, and tmin is added back to the hit t. The scenes also rebase rays
//    whose start point lies on a voxel boundary (see quad_scene.hpp).
//  - rtcIntersect16 needs its valid mask and packet 64-byte aligned.
//  - Embree's traversal is not exact at the edges of the interval or along planes; see
//    widen() and the nudge in packet::load for what the scenes do about it.
#pragma once
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <mutex>
#include <span>
#include <thread>
#include <vector>

#include <embree3/rtcore.h>
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

// The voxel containing point p (voxel x covers [x, x+1)), when p lies inside `bounds`;
// otherwise an impossible coordinate that matches no voxel. The float comparison comes first
// so a far-away point never overflows the int conversion.
inline glm::ivec3 voxel_at(glm::vec3 p, const box3i& bounds) {
    constexpr int nowhere = std::numeric_limits<int>::min();
    for (int a = 0; a < 3; ++a)
        if (!(p[a] >= float(bounds.min[a]) && p[a] < float(bounds.max[a]))) return glm::ivec3(nowhere);
    return {int(std::floor(p.x)), int(std::floor(p.y)), int(std::floor(p.z))};
}

// Whether the ray starts on a voxel boundary plane that it crosses: some coordinate of the
// start point p is an integer on an axis where the direction d is not zero.
inline bool starts_on_plane(glm::vec3 p, glm::vec3 d) {
    for (int a = 0; a < 3; ++a)
        if (d[a] != 0.0f && p[a] == std::floor(p[a])) return true;
    return false;
}

// A bound a little above t, for Embree's tfar. Embree's node culling computes box entries
// with an approximate reciprocal and drops a box entered exactly at tfar (measured: a hit
// at t == tmax is lost). The scenes give Embree this widened bound and keep the exact one
// themselves (box callbacks compare against it; quad hits beyond it are discarded).
inline float widen(float t) { return t + std::abs(t) * 0x1p-16f + 0x1p-100f; }

// One 16-ray packet as Embree wants it, plus per-lane bookkeeping.
struct packet {
    alignas(64) int valid[packet_width];
    alignas(64) RTCRayHit16 rayhit;
    float shift[packet_width];  // tmin added back to Embree's t for rebased lanes, else 0
    bool boundary = false;      // set by a scene when some lane starts on a boundary plane

    // Loads r into lane i; `rebase` moves the origin to `start` (= start_point(r)) and
    // traces from tnear 0. Rays with tmin < 0 are always rebased. Both Embree geometry
    // types ignore the ray's time, mask and flags, which are set to neutral values.
    void load(unsigned i, const ray& r, glm::vec3 start, bool rebase) {
        rebase = rebase || r.tmin < 0.0f;
        glm::vec3 o = rebase ? start : r.origin;
        // +0.0f turns -0 into +0, so "which side of a plane" never depends on a zero's sign.
        glm::vec3 d = r.direction + 0.0f;
        // Along an axis with zero direction the ray never leaves its row of voxels, and where
        // in the row it runs changes neither which voxels it meets nor any t. So move it to
        // the middle of its row (voxel y covers [y, y+1)). Measured reasons: with o on a
        // boundary plane, Embree's node test computes (plane - o) * (1 / 0) = NaN and culls
        // the boxes of the ray's own row; and its watertight quad test hits the faces of the
        // row below on their edge, even with o moved up by one ulp. Beyond 2^22 floats are
        // too coarse for this, but no voxel lies there (coordinates stay below 2^20).
        for (int a = 0; a < 3; ++a)
            if (d[a] == 0.0f && std::abs(o[a]) < 0x1p22f) o[a] = std::floor(o[a]) + 0.5f;
        RTCRay16& p = rayhit.ray;
        p.org_x[i] = o.x; p.org_y[i] = o.y; p.org_z[i] = o.z;
        p.dir_x[i] = d.x; p.dir_y[i] = d.y; p.dir_z[i] = d.z;
        p.tnear[i] = rebase ? 0.0f : r.tmin;
        p.tfar[i] = rebase ? r.tmax - r.tmin : r.tmax;
        p.time[i] = 0.0f;
        p.mask[i] = 0xFFFFFFFFu;
        p.id[i] = i;  // callbacks find per-lane data in their context by this id
        p.flags[i] = 0;
        rayhit.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        rayhit.hit.primID[i] = RTC_INVALID_GEOMETRY_ID;
        rayhit.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
        shift[i] = rebase ? r.tmin : 0.0f;
        valid[i] = -1;
    }
    // Marks lane i inactive and fills it with harmless values.
    void park(unsigned i) {
        RTCRay16& p = rayhit.ray;
        p.org_x[i] = p.org_y[i] = p.org_z[i] = 0.0f;
        p.dir_x[i] = p.dir_y[i] = 0.0f;
        p.dir_z[i] = 1.0f;
        p.tnear[i] = 0.0f;
        p.tfar[i] = 0.0f;
        p.time[i] = 0.0f;
        p.mask[i] = 0;
        p.id[i] = i;
        p.flags[i] = 0;
        rayhit.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        shift[i] = 0.0f;
        valid[i] = 0;
    }
    bool any_valid() const {
        for (unsigned i = 0; i < packet_width; ++i)
            if (valid[i]) return true;
        return false;
    }
    // Embree's t for lane i in the caller's ray parameter. Adding +0.0f maps a -0 (Embree
    // reports one for a hit exactly at tnear) to +0.
    float t(unsigned i) const { return rayhit.ray.tfar[i] + shift[i] + 0.0f; }
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
