// The residency manager of a world on disk: which chunks are in memory. Each frame the
// caller asks for the cut its camera wants (request); a background thread reads the
// missing chunks' files, coarse LODs first, then nearer ones, while the resident bytes
// stay within a budget; commit() then takes what finished loading and evicts what the
// cut no longer needs. The top LOD is always resident, so every region has something to
// show: a chunk not (yet) resident is traced at the finest resident LOD above it.
// Corrupt or missing files are reported (errors()) and never shown.
#pragma once
#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "voxray/world/chunk_file.hpp"
#include "voxray/world/lod_select.hpp"
#include "voxray/world/manifest.hpp"
#include "voxray/world/world_blob.hpp"

namespace voxray {

struct residency_options {
    std::uint64_t budget_bytes = std::uint64_t(256) << 20;  // chunk files' bytes resident at most (the top LOD counts too)
    double streaming_factor = 2.0;
};

struct residency_stats {
    std::uint64_t resident_chunks = 0, resident_bytes = 0;
    std::uint64_t wanted_chunks = 0;       // in the last requested cut
    std::uint64_t queued = 0;              // waiting for, or in, the loader
    std::uint64_t loads = 0, evictions = 0, failures = 0;
    std::uint64_t skipped_for_budget = 0;  // wanted chunks left out of the last request by the budget
};

class residency_manager {
public:
    residency_manager(std::filesystem::path dir, residency_options options)
        : dir_(std::move(dir)), options_(options), manifest_(read_manifest(dir_)), tree_(manifest_) {
        for (auto& c : manifest_.chunks)
            if (c.key.lod == manifest_.grid.top_lod) pinned_.insert(c.key);
        std::uint64_t pinned_bytes = 0;
        for (auto& k : pinned_) pinned_bytes += file_bytes(k);
        if (pinned_bytes > options_.budget_bytes)
            fail("world ", dir_.string(), ": the budget of ", options_.budget_bytes, " bytes is less than the top LOD's ",
                 pinned_bytes, " bytes, which are always resident");
        load_pinned();
        planned_ = pinned_;
        loader_ = std::thread([this] { load_loop(); });
    }
    ~residency_manager() {
        {
            std::lock_guard lock(mutex_);
            stop_ = true;
        }
        wake_.notify_all();
        loader_.join();
    }
    residency_manager(const residency_manager&) = delete;
    residency_manager& operator=(const residency_manager&) = delete;

    // The cut the camera wants, and loads for its chunks that are not resident, in order
    // (coarse first, then nearer), until the budget is reached: the rest wait for a
    // later request, and show their stand-ins meanwhile. Replaces the last request.
    void request(glm::dvec3 camera) {
        wanted_.clear();
        planned_ = pinned_;
        std::uint64_t planned = 0;
        for (auto& k : pinned_) planned += file_bytes(k);
        std::vector<chunk_key> to_load;
        std::uint64_t skipped = 0;
        for (auto& choice : tree_.select(camera, options_.streaming_factor)) {
            wanted_.insert(choice.key);
            if (pinned_.count(choice.key)) continue;
            std::uint64_t bytes = file_bytes(choice.key);
            if (skipped || planned + bytes > options_.budget_bytes) {
                ++skipped;
                continue;
            }
            planned += bytes;
            planned_.insert(choice.key);
            if (!resident_.count(choice.key)) to_load.push_back(choice.key);
        }
        {
            std::lock_guard lock(mutex_);
            queue_.clear();
            std::set<chunk_key, chunk_key_less> arrived;  // loaded, not yet committed
            for (auto& c : loaded_) arrived.insert(c.key);
            for (auto& k : to_load)
                if (!failed_.count(k) && !arrived.count(k)) queue_.push_back(k);
            stats_.skipped_for_budget = skipped;
            stats_.wanted_chunks = wanted_.size();
        }
        wake_.notify_all();
    }

    // Takes the chunks loaded since the last commit that the last request planned, and
    // evicts every resident chunk it did not plan. The planned chunks fit the budget, and
    // stand-ins are among them (the pinned top LOD at least), so the resident bytes never
    // pass the budget. True when the resident set changed.
    bool commit() {
        std::vector<chunk_record> arrived;
        {
            std::lock_guard lock(mutex_);
            arrived.swap(loaded_);
        }
        bool changed = false;
        for (auto& c : arrived) {
            if (resident_.count(c.key) || !planned_.count(c.key)) continue;  // planned by an older request: dropped
            auto key = c.key;
            resident_.emplace(key, std::make_unique<chunk_record>(std::move(c)));
            changed = true;
        }
        // Stand-ins for the planned chunks still loading: the finest resident one above
        // each, kept while the budget the plan left over allows (else a coarser one,
        // down to the pinned top LOD, which is planned).
        std::set<chunk_key, chunk_key_less> keep = planned_;
        std::uint64_t room = options_.budget_bytes;
        for (auto& k : planned_) room -= std::min(room, resident_.count(k) ? file_bytes(k) : 0);
        for (auto& k : wanted_) {
            if (resident_.count(k)) continue;
            for (int n = k.lod + 1; n <= manifest_.grid.top_lod; ++n) {
                chunk_key up{n, k.cell >> (n - k.lod)};
                if (!resident_.count(up)) continue;
                if (keep.count(up)) break;
                if (file_bytes(up) <= room) {
                    room -= file_bytes(up);
                    keep.insert(up);
                    break;
                }
            }
        }
        for (auto it = resident_.begin(); it != resident_.end();) {
            if (keep.count(it->first)) {
                ++it;
                continue;
            }
            it = resident_.erase(it);
            ++evictions_;
            changed = true;
        }
        return changed;
    }

    // The resident chunks the rays should see: the wanted ones, and stand-ins for the
    // wanted ones not resident (pack_world applies them coarse to fine).
    std::vector<placement> placements() const {
        std::set<chunk_key, chunk_key_less> shown;
        for (auto& k : wanted_) {
            if (resident_.count(k))
                shown.insert(k);
            else if (auto stand_in = finest_resident_above(k))
                shown.insert(*stand_in);
        }
        if (wanted_.empty()) shown.insert(pinned_.begin(), pinned_.end());
        std::vector<placement> out;
        for (auto& k : shown) out.push_back({k, resident_.at(k).get()});
        return out;
    }

    // Blocks until the loader has nothing queued or in flight (tests, benchmarks, and a
    // demo that wants every frame complete).
    void wait_for_loads() {
        std::unique_lock lock(mutex_);
        idle_.wait(lock, [&] { return queue_.empty() && !busy_; });
    }

    const world_manifest& manifest() const { return manifest_; }
    const std::filesystem::path& folder() const { return dir_; }
    const chunk_record* resident(const chunk_key& k) const {
        auto it = resident_.find(k);
        return it == resident_.end() ? nullptr : it->second.get();
    }
    residency_stats stats() const {
        std::lock_guard lock(mutex_);
        residency_stats s = stats_;
        s.resident_chunks = resident_.size();
        for (auto& [k, c] : resident_) s.resident_bytes += file_bytes(k);
        s.queued = queue_.size() + (busy_ ? 1 : 0);
        s.evictions = evictions_;
        return s;
    }
    // The files that could not be loaded, each with the reader's error.
    std::vector<std::string> errors() const {
        std::lock_guard lock(mutex_);
        return errors_;
    }

private:
    std::uint64_t file_bytes(const chunk_key& k) const {
        auto* c = manifest_.find(k);
        return c ? c->file_bytes : 0;
    }
    std::optional<chunk_key> finest_resident_above(chunk_key k) const {
        for (int n = k.lod + 1; n <= manifest_.grid.top_lod; ++n) {
            chunk_key up{n, k.cell >> (n - k.lod)};
            if (resident_.count(up)) return up;
        }
        return std::nullopt;
    }
    // The chunk, or the reason it cannot be shown. Nothing escapes: a loader thread that
    // threw (std::bad_alloc under a memory limit, say) would end the process.
    std::optional<chunk_record> read(const chunk_key& k, std::string& failure) const {
        try {
            return read_listed_chunk(dir_, manifest_, k);
        } catch (const error& e) {
            failure = e.what();
        } catch (const std::exception& e) {
            failure = "chunk file " + chunk_file_path(dir_, k).string() + ": " + e.what();
        }
        return std::nullopt;
    }
    void failed(const chunk_key& k, std::string failure) {
        failed_.insert(k);
        errors_.push_back(std::move(failure));
        ++stats_.failures;
    }
    // The top LOD is what every region shows while nothing finer is resident: without
    // one of its chunks the world cannot be shown, so that is fatal, naming the file.
    void load_pinned() {
        for (auto& k : pinned_) {
            std::string failure;
            auto c = read(k, failure);
            if (!c) fail("world ", dir_.string(), ": a chunk of the top LOD (", manifest_.grid.top_lod,
                         "), which is always shown, cannot be loaded: ", failure);
            resident_.emplace(k, std::make_unique<chunk_record>(std::move(*c)));
            ++stats_.loads;
        }
    }
    void load_loop() {
        std::unique_lock lock(mutex_);
        for (;;) {
            wake_.wait(lock, [&] { return stop_ || !queue_.empty(); });
            if (stop_) return;
            chunk_key k = queue_.front();
            queue_.pop_front();
            busy_ = true;
            lock.unlock();
            std::string failure;
            std::optional<chunk_record> c = read(k, failure);
            lock.lock();
            busy_ = false;
            if (c) {
                loaded_.push_back(std::move(*c));
                ++stats_.loads;
            } else {
                failed(k, std::move(failure));
            }
            if (queue_.empty()) idle_.notify_all();
        }
    }

    std::filesystem::path dir_;
    residency_options options_;
    world_manifest manifest_;
    lod_tree tree_;
    std::set<chunk_key, chunk_key_less> pinned_, wanted_;
    std::set<chunk_key, chunk_key_less> planned_;  // of the last request: pinned, then wanted ones within the budget
    std::map<chunk_key, std::unique_ptr<chunk_record>, chunk_key_less> resident_;  // owned by the caller's thread
    std::uint64_t evictions_ = 0;

    mutable std::mutex mutex_;  // guards what the loader shares: the queue, arrivals, failures, stats
    std::condition_variable wake_, idle_;
    std::deque<chunk_key> queue_;
    std::vector<chunk_record> loaded_;
    std::set<chunk_key, chunk_key_less> failed_;
    std::vector<std::string> errors_;
    residency_stats stats_;
    bool busy_ = false, stop_ = false;
    std::thread loader_;
};

}  // namespace voxray
