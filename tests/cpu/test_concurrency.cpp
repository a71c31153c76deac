// A CPU tracer, like a committed Embree scene, may be called from any number of threads at
// once: every call must complete, with the same hits as when it runs alone. Also the pool
// underneath (overlapping parallel_for calls, exceptions back to their own caller) and
// single-ray calls, which run on the calling thread.
//
// If calls deadlock again, the watchdog ends the process with a failure instead of letting
// ctest wait (the TIMEOUT property is the second guard).
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <future>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "random_models.hpp"
#include "voxray/brickmap/brickmap.hpp"
#include "voxray/check/ray_sets.hpp"
#include "voxray/cpu.hpp"
#include "voxray/cpu/thread_pool.hpp"
#include "voxray/dense_grid/dense_grid.hpp"

using namespace voxray;

namespace {

// Generous: the work below takes well under a second in Release, some seconds under TSan.
constexpr auto watchdog_timeout = std::chrono::seconds(120);

// Runs `work` on its own thread; if it has not finished in time, the process ends here,
// since a deadlocked thread can be neither joined nor abandoned by gtest.
void with_watchdog(const char* what, const std::function<void()>& work) {
    auto done = std::async(std::launch::async, work);
    if (done.wait_for(watchdog_timeout) != std::future_status::ready) {
        std::fprintf(stderr, "FAILED: %s did not finish within %lld s (deadlock?)\n", what,
                     static_cast<long long>(watchdog_timeout.count()));
        std::fflush(stdout);
        std::fflush(stderr);
        std::quick_exit(EXIT_FAILURE);
    }
    done.get();  // rethrows what `work` threw
}

// Starts `threads` std::threads running body(thread index) and joins them all.
void on_threads(unsigned threads, const std::function<void(unsigned)>& body) {
    std::vector<std::thread> pool;
    for (unsigned t = 0; t < threads; ++t) pool.emplace_back(body, t);
    for (auto& t : pool) t.join();
}

std::size_t count_differences(const std::vector<hit>& a, const std::vector<hit>& b) {
    if (a.size() != b.size()) return std::max(a.size(), b.size());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
        if (std::memcmp(&a[i], &b[i], sizeof(hit)) != 0) ++differ;
    return differ;
}

// Ray sets of one, part of one, exactly one, and several batches: the single-batch path
// and the pool both run concurrently.
std::vector<std::vector<ray>> ray_sets(const box3i& bounds) {
    std::vector<std::vector<ray>> sets;
    std::uint64_t seed = 100;
    for (std::size_t n : {std::size_t(1), std::size_t(300), cpu_detail::batch_rays, cpu_detail::batch_rays + 1,
                          std::size_t(3000), std::size_t(9000)})
        sets.push_back(check_rays(bounds, 2, n, seed++));
    return sets;
}

// Many threads call closest_hit and any_hit on ONE shared tracer, each going through the
// ray sets in its own order; every result must equal a single-threaded reference.
template <class Structure>
void expect_concurrent_calls_match_reference(const Structure& structure, const box3i& bounds, unsigned callers,
                                             unsigned pool_threads) {
    auto sets = ray_sets(bounds);
    std::vector<std::vector<hit>> closest(sets.size()), any(sets.size());
    {
        tracer<cpu, Structure> alone(structure, {1});
        for (std::size_t s = 0; s < sets.size(); ++s) {
            closest[s].resize(sets[s].size());
            any[s].resize(sets[s].size());
            alone.closest_hit(sets[s], closest[s]);
            alone.any_hit(sets[s], any[s]);
        }
    }
    tracer<cpu, Structure> shared(structure, {pool_threads});
    constexpr int calls_per_thread = 60;
    std::atomic<std::size_t> wrong_calls{0}, calls{0};
    with_watchdog("concurrent tracer calls", [&] {
        on_threads(callers, [&](unsigned t) {
            std::vector<hit> hits;
            for (int k = 0; k < calls_per_thread; ++k) {
                std::size_t s = (t * 7 + std::size_t(k)) % sets.size();
                bool any_hit = (t + std::size_t(k)) % 2 == 1;
                hits.assign(sets[s].size(), hit{});
                if (any_hit) shared.any_hit(sets[s], hits);
                else shared.closest_hit(sets[s], hits);
                if (count_differences(hits, any_hit ? any[s] : closest[s]) != 0) ++wrong_calls;
                ++calls;
            }
        });
    });
    EXPECT_EQ(calls.load(), std::size_t(callers) * calls_per_thread);
    EXPECT_EQ(wrong_calls.load(), 0u) << "calls whose hits differ from the single-threaded reference";
}

TEST(cpu_concurrency, dense_grid_shared_by_threads) {
    voxel_model model = test::random_model(40, 0.03f, 7);
    dense_grid grid(model);
    // More pool threads than cores, and the default, so that calls overlap in the pool.
    expect_concurrent_calls_match_reference(grid, model.bounds(), 6, 4);
    expect_concurrent_calls_match_reference(grid, model.bounds(), 3, 0);
}

TEST(cpu_concurrency, brickmap_shared_by_threads) {
    voxel_model model = test::random_model(48, 0.02f, 8, {-5, 3, -20});
    brickmap<> map(model);
    expect_concurrent_calls_match_reference(map, model.bounds(), 6, 4);
    expect_concurrent_calls_match_reference(map, model.bounds(), 2, 0);
}

// ---- the pool itself ----

TEST(thread_pool, concurrent_calls_each_see_all_their_indices_once) {
    cpu_detail::thread_pool pool(4);
    constexpr unsigned callers = 6;
    constexpr int calls_per_thread = 2000;
    std::atomic<std::size_t> wrong_calls{0};
    with_watchdog("concurrent parallel_for", [&] {
        on_threads(callers, [&](unsigned t) {
            for (int k = 0; k < calls_per_thread; ++k) {
                std::size_t n = std::size_t((t * 31 + unsigned(k) * 17) % 97);  // 0 and 1 included
                std::vector<std::atomic<int>> seen(n);
                pool.parallel_for(n, [&](std::size_t i) { seen.at(i).fetch_add(1); });
                for (auto& s : seen)
                    if (s.load() != 1) { ++wrong_calls; break; }
            }
        });
    });
    EXPECT_EQ(wrong_calls.load(), 0u);
}

TEST(thread_pool, an_exception_goes_back_to_its_own_caller_only) {
    cpu_detail::thread_pool pool(4);
    constexpr unsigned callers = 5;
    constexpr int calls_per_thread = 1000;
    std::atomic<std::size_t> wrong{0};
    with_watchdog("parallel_for with exceptions", [&] {
        on_threads(callers, [&](unsigned t) {
            const bool throws = t % 2 == 0;
            for (int k = 0; k < calls_per_thread; ++k) {
                std::vector<std::atomic<int>> seen(50);
                try {
                    pool.parallel_for(seen.size(), [&](std::size_t i) {
                        seen[i].fetch_add(1);
                        if (throws && i == 17) throw std::runtime_error("caller " + std::to_string(t));
                    });
                    if (throws) ++wrong;  // its exception was lost
                    for (auto& s : seen)
                        if (s.load() != 1) { ++wrong; break; }
                } catch (const std::runtime_error& e) {
                    if (!throws || e.what() != "caller " + std::to_string(t)) ++wrong;  // someone else's
                }
            }
        });
    });
    EXPECT_EQ(wrong.load(), 0u);
    // The pool still works after all that.
    std::atomic<int> sum{0};
    pool.parallel_for(100, [&](std::size_t i) { sum += int(i); });
    EXPECT_EQ(sum.load(), 4950);
}

TEST(thread_pool, a_job_may_call_parallel_for_itself) {
    cpu_detail::thread_pool pool(3);
    std::atomic<int> inner{0};
    with_watchdog("nested parallel_for", [&] {
        pool.parallel_for(8, [&](std::size_t) { pool.parallel_for(10, [&](std::size_t) { ++inner; }); });
    });
    EXPECT_EQ(inner.load(), 80);
}

TEST(thread_pool, destroys_cleanly_idle_or_after_work) {
    with_watchdog("pool destruction", [] {
        for (unsigned threads : {1u, 2u, 5u}) {
            { cpu_detail::thread_pool idle(threads); }
            cpu_detail::thread_pool used(threads);
            std::atomic<int> n{0};
            used.parallel_for(1000, [&](std::size_t) { ++n; });
            EXPECT_EQ(n.load(), 1000);
            EXPECT_EQ(used.size(), threads);
        }
    });
}

// ---- single rays ----

// One ray at a time (the calling thread, no pool) gives exactly the hits of one big call.
template <class Structure>
void expect_single_ray_calls_match_batch(const Structure& structure, const box3i& bounds) {
    tracer<cpu, Structure> t(structure, {4});
    auto rays = check_rays(bounds, 2, 3000, 31);
    std::vector<hit> batch(rays.size()), single(rays.size());
    for (int mode = 0; mode < 2; ++mode) {
        if (mode == 0) t.closest_hit(rays, batch);
        else t.any_hit(rays, batch);
        for (std::size_t i = 0; i < rays.size(); ++i) {
            std::span<const ray> one(&rays[i], 1);
            std::span<hit> out(&single[i], 1);
            if (mode == 0) t.closest_hit(one, out);
            else t.any_hit(one, out);
        }
        EXPECT_EQ(count_differences(single, batch), 0u) << "of " << rays.size() << " rays, mode " << mode;
    }
}

TEST(cpu_concurrency, single_ray_calls_match_batch_dense) {
    voxel_model model = test::hollow_box(30, {-7, 2, 0});
    expect_single_ray_calls_match_batch(dense_grid(model), model.bounds());
}

TEST(cpu_concurrency, single_ray_calls_match_batch_brickmap) {
    voxel_model model = test::random_model(40, 0.03f, 9);
    expect_single_ray_calls_match_batch(brickmap<>(model), model.bounds());
}

}  // namespace
