// A small persistent pool: parallel_for(n, f) runs f(i) for every i in [0, n) on the
// calling thread and whichever workers are free. Calls may come from several threads at
// once (a tracer is shared like a committed Embree scene), and from inside f: each call
// is a job of its own, with its own index counter, helpers and error, in a queue that
// idle workers take from. The caller always works on its own job too, so no call ever
// waits for a free worker, only for the workers already helping it to finish.
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

    // Runs body(i) for every i in [0, count); rethrows, to this caller only, the first
    // exception its body threw (the indices not yet handed out are then skipped).
    void parallel_for(std::size_t count, const std::function<void(std::size_t)>& body) {
        if (count <= 1 || workers_.empty()) {  // nothing to share: waking a worker costs more than it saves
            for (std::size_t i = 0; i < count; ++i) body(i);
            return;
        }
        job j(body, count);
        {
            std::lock_guard lock(mutex_);
            pending_.push_back(&j);
        }
        // Wake only as many workers as there are indices besides the caller's.
        for (std::size_t k = 1; k < std::min<std::size_t>(count, size()); ++k) wake_.notify_one();
        run(j);
        std::unique_lock lock(mutex_);
        std::erase(pending_, &j);  // no worker joins it from now on...
        j.idle.wait(lock, [&] { return j.helpers == 0; });  // ...and those that did are done: j may die
        if (j.error) std::rethrow_exception(j.error);
    }

private:
    // One parallel_for call; it lives on its caller's stack. `helpers` and `error` are
    // guarded by the pool's mutex, indices are handed out through `next`.
    struct job {
        job(const std::function<void(std::size_t)>& b, std::size_t n) : body(&b), count(n) {}
        const std::function<void(std::size_t)>* body;
        std::size_t count;
        std::atomic<std::size_t> next{0};
        unsigned helpers = 0;  // workers inside run(*this)
        std::condition_variable idle;  // helpers dropped to 0
        std::exception_ptr error;
    };

    void run(job& j) {
        for (std::size_t i; (i = j.next.fetch_add(1)) < j.count;) {
            try {
                (*j.body)(i);
            } catch (...) {
                std::lock_guard lock(mutex_);
                if (!j.error) j.error = std::current_exception();
                j.next.store(j.count);
            }
        }
    }

    void work() {
        std::unique_lock lock(mutex_);
        for (;;) {
            wake_.wait(lock, [this] { return stopping_ || !pending_.empty(); });
            if (stopping_) return;
            job& j = *pending_.front();  // the oldest call first: it has waited longest
            ++j.helpers;
            lock.unlock();
            run(j);
            lock.lock();
            std::erase(pending_, &j);  // all its indices are handed out: send nobody else there
            if (--j.helpers == 0) j.idle.notify_one();  // under the lock: its caller cannot free j before this
        }
    }

    std::vector<std::thread> workers_;
    std::mutex mutex_;
    std::condition_variable wake_;
    std::vector<job*> pending_;  // calls that may still have indices to hand out
    bool stopping_ = false;
};

}  // namespace voxray::cpu_detail
