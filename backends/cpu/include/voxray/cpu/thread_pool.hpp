// A small persistent pool: parallel_for(n, f) runs f(i) for i in [0, n) on all workers
// and the calling thread, handing out indices through one atomic counter.
#pragma once
#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace voxray::cpu_detail {

class thread_pool {
public:
    explicit thread_pool(unsigned threads = 0) {
        if (threads == 0) threads = std::max(1u, std::thread::hardware_concurrency());
        for (unsigned i = 1; i < threads; ++i) workers_.emplace_back([this] { work(); });
    }
    ~thread_pool() {
        {
            std::lock_guard lock(mutex_);
            stopping_ = true;
        }
        wake_.notify_all();
        for (auto& w : workers_) w.join();
    }
    thread_pool(const thread_pool&) = delete;
    thread_pool& operator=(const thread_pool&) = delete;

    unsigned size() const { return unsigned(workers_.size()) + 1; }

    // Runs job(i) for every i in [0, count); rethrows the first exception a job threw.
    void parallel_for(std::size_t count, const std::function<void(std::size_t)>& job) {
        std::unique_lock lock(mutex_);
        job_ = &job;
        count_ = count;
        next_.store(0);
        error_ = nullptr;
        busy_ = workers_.size();
        ++generation_;
        lock.unlock();
        wake_.notify_all();
        run_jobs();
        lock.lock();
        done_.wait(lock, [this] { return busy_ == 0; });
        job_ = nullptr;
        if (error_) std::rethrow_exception(error_);
    }

private:
    void run_jobs() {
        for (std::size_t i; (i = next_.fetch_add(1)) < count_;) {
            try {
                (*job_)(i);
            } catch (...) {
                std::lock_guard lock(error_mutex_);
                if (!error_) error_ = std::current_exception();
                next_.store(count_);
            }
        }
    }
    void work() {
        std::uint64_t seen = 0;
        for (;;) {
            std::unique_lock lock(mutex_);
            wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
            if (stopping_) return;
            seen = generation_;
            lock.unlock();
            run_jobs();
            lock.lock();
            if (--busy_ == 0) done_.notify_one();
        }
    }

    std::vector<std::thread> workers_;
    std::mutex mutex_, error_mutex_;
    std::condition_variable wake_, done_;
    const std::function<void(std::size_t)>* job_ = nullptr;
    std::size_t count_ = 0;
    std::atomic<std::size_t> next_{0};
    std::size_t busy_ = 0;
    std::uint64_t generation_ = 0;
    bool stopping_ = false;
    std::exception_ptr error_;
};

}  // namespace voxray::cpu_detail
