// Plain std::thread fan-out for the model builders (voxelizer, procedural
// scenes, solid fill). Every id in [0, threads) runs exactly once, even when the
// system refuses to start a thread (the caller then runs the missing ids itself);
// all threads are joined before returning, and the first exception is rethrown
// on the caller's thread, so a failure never leaves a joinable thread behind.
#pragma once
#include <algorithm>
#include <cstddef>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace voxray {

// More threads than this only add overhead for these builders.
inline constexpr unsigned max_build_threads = 256;

// 0 means all hardware threads; never more than `useful` (at least 1).
inline unsigned resolve_build_threads(unsigned requested, std::size_t useful) {
    unsigned n = requested ? requested : std::max(1u, std::thread::hardware_concurrency());
    n = std::min(n, max_build_threads);
    if (useful < n) n = unsigned(std::max<std::size_t>(useful, 1));
    return n;
}

// Calls work(id) for every id in [0, threads).
template <class Work>
void run_build_threads(unsigned threads, Work&& work) {
    std::exception_ptr failure;
    std::mutex failure_mutex;
    auto guarded = [&](unsigned id) {
        try {
            work(id);
        } catch (...) {
            std::lock_guard lock(failure_mutex);
            if (!failure) failure = std::current_exception();
        }
    };
    std::vector<std::thread> pool;
    try {
        pool.reserve(threads);
        for (unsigned id = 1; id < threads; ++id) pool.emplace_back(guarded, id);
    } catch (...) {
        // Out of threads or memory: the ids not started run here below.
    }
    guarded(0);
    for (auto id = unsigned(pool.size()) + 1; id < threads; ++id) guarded(id);
    for (auto& t : pool) t.join();
    if (failure) std::rethrow_exception(failure);
}

}  // namespace voxray
