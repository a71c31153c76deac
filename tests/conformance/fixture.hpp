// The typed fixture all conformance suites share. A case is trace_case<Backend,
// Structure>; what it is held to:
//   the oracle     a brute-force slab test of every voxel (support/brute_force.hpp), on
//                  small models, sharing no code with any traversal;
//   the reference  the dense grid traced by cpu_scalar on one thread, on larger ones;
//   cpu_scalar     the same structure traced by cpu_scalar on one thread: every backend
//                  must give the same hit records bit for bit (t = -0 vs +0 aside).
// Closest hits agree under compare_hits (ties at edges and corners are counted, not
// failed); any hits agree on whether a hit exists.
#pragma once
#include <cmath>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "brute_force.hpp"
#include "hit_bits.hpp"
#include "typed_cases.hpp"
#include "voxray/check/compare.hpp"
#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/tracer.hpp"

namespace voxray::test {

// What a backend promises about float arithmetic. Exact (IEEE, correctly rounded
// division) means bit-identical hits to cpu_scalar; a device without that must still
// agree with no mismatches and no ties. Backends that may run on a GPU specialize this.
// signed_zero_t: the device may return t = -0 where the CPU says +0 (and nothing else).
template <class Backend>
struct float_rules {
    static constexpr bool signed_zero_t = false;
    template <class Engine>
    static bool exact(Engine&) { return true; }
};

enum class mode { closest, any };
inline const char* mode_name(mode m) { return m == mode::any ? "any hit" : "closest hit"; }

template <class Tracer>
std::vector<hit> trace(Tracer& t, std::span<const ray> rays, mode m) {
    std::vector<hit> hits(rays.size());
    if (m == mode::any) t.any_hit(rays, hits);
    else t.closest_hit(rays, hits);
    return hits;
}

inline cpu_options one_thread() { return cpu_options{1}; }

// The oracle's and the reference's hits depend on the model and the rays alone, and every
// structure x backend of a suite asks for the same ones: each is computed once a process.
// Keyed by the rays' bytes (compared whole) and a hash of the model's voxels.
template <class Compute>
std::vector<hit> remembered_hits(int kind, const voxel_model& model, std::span<const ray> rays, Compute&& compute) {
    struct entry {
        int kind;
        std::uint64_t model_hash;
        std::vector<ray> rays;
        std::vector<hit> hits;
    };
    static std::mutex mutex;
    static std::vector<entry> known;
    std::uint64_t h = 0xcbf29ce484222325ull;
    model.for_each_voxel([&](glm::ivec3 p, std::uint8_t v) {
        for (std::int32_t w : {p.x, p.y, p.z, std::int32_t(v)}) h = (h ^ std::uint32_t(w)) * 0x100000001b3ull;
    });
    auto same_rays = [&](const std::vector<ray>& r) {
        return r.size() == rays.size() && (rays.empty() || std::memcmp(r.data(), rays.data(), rays.size_bytes()) == 0);
    };
    {
        std::lock_guard lock(mutex);
        for (auto& e : known)
            if (e.kind == kind && e.model_hash == h && same_rays(e.rays)) return e.hits;
    }
    auto hits = compute();
    std::lock_guard lock(mutex);
    known.push_back({kind, h, std::vector<ray>(rays.begin(), rays.end()), hits});
    return hits;
}

// Closest hits of the reference: the dense grid of `model` on cpu_scalar, one thread.
inline std::vector<hit> reference_hits(const voxel_model& model, std::span<const ray> rays) {
    return remembered_hits(0, model, rays, [&] {
        dense_grid grid(model);
        tracer<cpu_scalar, dense_grid> t(grid, one_thread());
        return trace(t, rays, mode::closest);
    });
}

inline std::vector<hit> oracle_hits(const voxel_model& model, std::span<const ray> rays) {
    return remembered_hits(1, model, rays, [&] {
        std::vector<hit> hits;
        hits.reserve(rays.size());
        for (const ray& r : rays) hits.push_back(brute_force_trace(model, r));
        return hits;
    });
}

// One ray's verdict: closest hits by compare_hits; an any hit only by whether it exists
// (a disagreement is a tie where the one hit grazes its voxel or lies at tmax).
inline agreement judge(const ray& r, const hit& expected_closest, const hit& got, mode m) {
    if (m == mode::closest || got.is_hit() != expected_closest.is_hit())
        return compare_hits(r, expected_closest, got);
    return agreement::same;
}

// Counts agreement of `got` with `expected` (closest hits) and fails on any mismatch,
// showing the first few.
inline agreement_counts expect_agreement(const std::string& what, std::span<const ray> rays,
                                         std::span<const hit> expected, std::span<const hit> got, mode m) {
    agreement_counts counts;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        agreement a = judge(rays[i], expected[i], got[i], m);
        counts.add(a);
        if (a == agreement::mismatch && counts.mismatches <= 5)
            ADD_FAILURE() << what << " (" << mode_name(m) << "), ray " << i << ": " << describe(rays[i])
                          << "\n  expected " << describe(expected[i]) << "\n  got      " << describe(got[i]);
    }
    EXPECT_EQ(counts.mismatches, 0u) << what << " (" << mode_name(m) << ")";
    return counts;
}

inline std::size_t count_hits(std::span<const hit> hits) {
    std::size_t n = 0;
    for (const hit& h : hits) n += h.is_hit();
    return n;
}

template <class Case>
struct conformance : ::testing::Test {
    using backend = typename Case::backend;
    using structure = typename Case::structure;
    using tracer_type = tracer<backend, structure>;

    static std::string case_name() { return case_names::GetName<Case>(0); }

    static void report(const std::string& what, const agreement_counts& c) {
        std::printf("[%s] %-40s %7llu rays: %7llu same, %5llu ties, %llu mismatches\n", case_name().c_str(),
                    what.c_str(), (unsigned long long)c.rays, (unsigned long long)c.same,
                    (unsigned long long)c.ties, (unsigned long long)c.mismatches);
    }

    // Closest and any hits of the structure built from `model`, on the backend under
    // test, against expected closest hits. Returns the closest hits' counts.
    static agreement_counts expect_agrees(const std::string& what, const voxel_model& model,
                                          std::span<const ray> rays, std::span<const hit> expected) {
        structure s(model);
        tracer_type t(s);
        agreement_counts closest;
        for (mode m : {mode::closest, mode::any}) {
            auto got = trace(t, rays, m);
            auto c = expect_agreement(what, rays, expected, got, m);
            if (m == mode::closest) closest = c;
            report(what + (m == mode::any ? " (any)" : ""), c);
        }
        return closest;
    }
    static agreement_counts expect_agrees_with_oracle(const std::string& what, const voxel_model& model,
                                                      std::span<const ray> rays) {
        return expect_agrees(what + " vs oracle", model, rays, oracle_hits(model, rays));
    }
    static agreement_counts expect_agrees_with_reference(const std::string& what, const voxel_model& model,
                                                         std::span<const ray> rays) {
        return expect_agrees(what + " vs reference", model, rays, reference_hits(model, rays));
    }

    // The closest hits of `rays` (oracle-checked in both modes): for exact expectations.
    static std::vector<hit> traced(const voxel_model& model, std::span<const ray> rays) {
        auto expected = oracle_hits(model, rays);
        structure s(model);
        tracer_type t(s);
        expect_agreement(case_name(), rays, expected, trace(t, rays, mode::any), mode::any);
        auto hits = trace(t, rays, mode::closest);
        expect_agreement(case_name(), rays, expected, hits, mode::closest);
        return hits;
    }
    static hit traced(const voxel_model& model, ray r) { return traced(model, std::span<const ray>(&r, 1))[0]; }

    // Every hit record of tracer `t` equals cpu_scalar's (one thread) on structure `s`,
    // in both modes; a backend without exact floats must still agree without ties.
    // Returns the number of closest hits, so that callers can refuse a vacuous pass.
    static std::size_t expect_bit_identical(const std::string& what, tracer_type& t, const structure& s,
                                            std::span<const ray> rays) {
        tracer<cpu_scalar, structure> scalar(s, one_thread());
        bool exact = float_rules<backend>::exact(t.engine());
        std::size_t hits = 0;
        for (mode m : {mode::closest, mode::any}) {
            auto want = trace(scalar, rays, m), got = trace(t, rays, m);
            if (m == mode::closest) hits = count_hits(want);
            std::size_t different = 0, zero_sign = 0;
            agreement_counts c;
            for (std::size_t i = 0; i < rays.size(); ++i) {
                c.add(m == mode::closest ? compare_hits(rays[i], want[i], got[i])
                                         : judge(rays[i], want[i], got[i], m));
                zero_sign += differ_in_zero_sign(want[i], got[i]);
                if (float_rules<backend>::signed_zero_t ? same_bits(want[i], got[i]) : identical(want[i], got[i]))
                    continue;
                if (exact && ++different <= 5)
                    ADD_FAILURE() << what << " (" << mode_name(m) << "), ray " << i << ": " << describe(rays[i])
                                  << "\n  cpu_scalar " << describe(want[i]) << "\n  " << backend::name << "  "
                                  << describe(got[i]);
            }
            EXPECT_EQ(c.mismatches, 0u) << what << " (" << mode_name(m) << ")";
            if (!exact) {
                EXPECT_EQ(c.ties, 0u) << what << " (" << mode_name(m) << ")";
            }
            std::printf("[%s] %-40s %7zu rays: %s%s (t = -0 vs +0 on %zu)\n",
                        case_name().c_str(), (what + (m == mode::any ? " (any)" : "")).c_str(), rays.size(),
                        exact ? "bit-identical to cpu_scalar" : "inexact floats: agreement only",
                        different ? " FAILED" : "", zero_sign);
        }
        return hits;
    }
};

}  // namespace voxray::test
