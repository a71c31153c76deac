// A chunked world streamed from disk (a folder that world/build/world_build.hpp wrote): the
// residency manager keeps a budget of chunks in memory for the camera, and the blob holds
// the directory of the current cut plus the shown chunks' DAGs in a pool. An update
// writes only what changed (new DAGs into free pool space, the directory) and logs those
// words under a new generation (sync/change_log.hpp), so that every tracer of the world,
// on any backend, sends its device just what it is missing (tracer::update asks
// changes_since its own generation). The blob changes only in update(), whole chunks at a
// time: rays never see a half-loaded chunk. Same kernel and layout as chunked_world
// (world/kernel.h).
#pragma once
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <iterator>
#include <map>
#include <mutex>
#include <shared_mutex>
#include <span>
#include <string_view>
#include <vector>

#include "voxray/core/word_range.hpp"
#include "voxray/sync/change_log.hpp"
#include "voxray/sync/sync_frame.hpp"
#include "voxray/world/stream/residency.hpp"
#include "voxray/world/world.hpp"

namespace voxray {

class streamed_world {
public:
    static constexpr std::string_view name = "world-streamed";
    using kernel = kernels::world_kernel;

    explicit streamed_world(const std::filesystem::path& dir, residency_options options = {})
        : residency_(dir, options) {
        repack();
    }

    // One frame of streaming for a camera at `camera` (world voxels): asks for its cut,
    // takes the chunks that finished loading, evicts, and re-places. `wait`: first wait
    // until every load asked for is done (a complete frame; else the frame shows stand-ins
    // for what is still loading). True when the blob changed.
    bool update(glm::dvec3 camera, bool wait = false) {
        residency_.request(camera);
        if (wait) residency_.wait_for_loads();
        std::unique_lock lock(sync_);  // tracers updating from other threads wait
        bool changed = residency_.commit();
        changed = repack() || changed;
        return changed;
    }

    std::span<const std::uint32_t> blob() const { return words_; }
    std::size_t bytes() const { return words_.size() * sizeof(std::uint32_t); }

    // For tracers (tracer.hpp, syncs_by_generation): the blob as it is and its generation,
    // and the words changed after generation g. update() waits while a frame lives.
    sync_frame snapshot() const {
        std::unique_lock lock(sync_);
        return {std::move(lock), words_, {}, log_.generation(), 0};
    }
    sync_frame changes_since(std::uint64_t g) const {
        std::unique_lock lock(sync_);
        return {std::move(lock), words_, log_.since(g, std::uint32_t(words_.size())), log_.generation(), 0};
    }
    // The words changed since the last call (all of them the first time, and after the
    // blob was reallocated), for one consumer that copies the blob itself; tracers ask
    // changes_since with their own generations instead.
    std::vector<word_range> take_dirty_ranges() {
        auto frame = changes_since(taken_);
        taken_ = frame.generation;
        return std::move(frame.ranges);
    }
    box3i bounds() const { return residency_.manifest().bounds; }
    const world_manifest& manifest() const { return residency_.manifest(); }
    const residency_manager& residency() const { return residency_; }
    residency_manager& residency() { return residency_; }
    // DAG words in the pool now, of the chunks the rays see.
    std::uint64_t shown_dag_bytes() const {
        std::uint64_t n = 0;
        for (auto& [k, s] : slots_) n += s.words * 4;
        return n;
    }
    std::uint64_t shown_chunks() const { return slots_.size(); }

private:
    struct slot {
        std::uint64_t offset = 0, words = 0;
    };
    // Places the residency manager's cut: frees the slots of chunks no longer shown,
    // copies new ones into free space (growing the pool when none fits), rewrites the
    // directory. True when anything changed.
    bool repack() {
        auto cut = residency_.placements();
        std::vector<chunk_key> keys;
        for (auto& p : cut) keys.push_back(p.key);
        if (!words_.empty() && keys == shown_keys_) return false;  // the same chunks: nothing to write
        shown_keys_ = std::move(keys);
        world_directory dir(residency_.manifest().grid, cut, residency_.manifest().attributes);
        auto shown = dir.chunks();
        std::map<chunk_key, const chunk_record*, chunk_key_less> wanted;
        for (auto* c : shown) wanted[c->key] = c;
        bool changed = false;
        for (auto it = slots_.begin(); it != slots_.end();) {
            if (wanted.count(it->first)) {
                ++it;
                continue;
            }
            release(it->second);
            it = slots_.erase(it);
            changed = true;
        }
        std::uint64_t directory_words = dir.words();
        bool relocate = directory_words > directory_capacity_;
        std::uint64_t need = 0;
        for (auto& [k, c] : wanted)
            if (!slots_.count(k)) need += c->dag.size();
        if (relocate || need > largest_free()) {
            reallocate(std::max(directory_words * 2, directory_capacity_), wanted);
            changed = true;
        }
        for (auto& [k, c] : wanted) {
            if (slots_.count(k)) continue;
            slot s{allocate(c->dag.size()), c->dag.size()};
            std::copy(c->dag.begin(), c->dag.end(), words_.begin() + std::ptrdiff_t(s.offset));
            dirty_.push_back({std::uint32_t(s.offset), std::uint32_t(s.words)});
            slots_[k] = s;
            changed = true;
        }
        std::vector<std::uint32_t> directory(directory_words);
        dir.write(directory, [&](const chunk_record* c) { return slots_.at(c->key).offset; });
        std::uint64_t span = std::max(directory_words, directory_used_);
        if (changed || !std::equal(directory.begin(), directory.end(), words_.begin())) {
            std::copy(directory.begin(), directory.end(), words_.begin());
            std::fill(words_.begin() + std::ptrdiff_t(directory_words), words_.begin() + std::ptrdiff_t(span), 0u);
            dirty_.push_back({0u, std::uint32_t(span)});
            changed = true;
        }
        directory_used_ = directory_words;
        log_.commit(std::exchange(dirty_, {}), std::exchange(relaid_out_, false), std::uint32_t(words_.size()));
        return changed;
    }

    // A new blob: the directory area, then the shown DAGs kept, packed, and free space
    // for those to come (twice the budget's worth of the pool, or what is needed).
    void reallocate(std::uint64_t directory_capacity, const std::map<chunk_key, const chunk_record*, chunk_key_less>& wanted) {
        directory_capacity_ = std::max<std::uint64_t>(directory_capacity, 4096);
        std::uint64_t dags = 0;
        for (auto& [k, c] : wanted) dags += c->dag.size();
        std::uint64_t pool = std::max<std::uint64_t>(dags * 2, std::uint64_t(1) << 16);
        check_blob_size("world-streamed", directory_capacity_ + pool);
        blob_words next(directory_capacity_ + pool, 0u);
        std::map<chunk_key, slot, chunk_key_less> kept;
        std::uint64_t cursor = directory_capacity_;
        for (auto& [k, s] : slots_) {
            std::copy(words_.begin() + std::ptrdiff_t(s.offset), words_.begin() + std::ptrdiff_t(s.offset + s.words),
                      next.begin() + std::ptrdiff_t(cursor));
            kept[k] = {cursor, s.words};
            cursor += s.words;
        }
        words_ = std::move(next);
        slots_ = std::move(kept);
        free_.clear();
        if (cursor < words_.size()) free_[cursor] = words_.size() - cursor;
        dirty_.clear();
        relaid_out_ = true;  // every tracer takes the new blob whole
        directory_used_ = 0;
    }

    std::uint64_t largest_free() const {
        std::uint64_t n = 0;
        for (auto& [at, size] : free_) n = std::max(n, size);
        return n;
    }
    // First fit; the caller made sure a range is large enough.
    std::uint64_t allocate(std::uint64_t words) {
        for (auto it = free_.begin(); it != free_.end(); ++it) {
            if (it->second < words) continue;
            std::uint64_t at = it->first, rest = it->second - words;
            free_.erase(it);
            if (rest) free_[at + words] = rest;
            return at;
        }
        fail("world-streamed: no free range of ", words, " words in the pool");
    }
    void release(const slot& s) {
        auto [it, inserted] = free_.emplace(s.offset, s.words);
        auto next = std::next(it);
        if (next != free_.end() && it->first + it->second == next->first) it->second += next->second, free_.erase(next);
        if (it != free_.begin()) {
            auto prev = std::prev(it);
            if (prev->first + prev->second == it->first) prev->second += it->second, free_.erase(it);
        }
    }

    residency_manager residency_;
    blob_words words_;
    std::uint64_t directory_capacity_ = 0, directory_used_ = 0;
    std::map<chunk_key, slot, chunk_key_less> slots_;
    std::map<std::uint64_t, std::uint64_t> free_;  // offset -> words
    std::vector<word_range> dirty_;  // of the repack under way, then logged
    bool relaid_out_ = false;        // the repack under way reallocated the blob
    change_log log_;                 // the words each repack changed, by generation
    std::uint64_t taken_ = 0;        // the generation take_dirty_ranges() handed out last
    mutable std::shared_mutex sync_;  // held by update() and by the frames tracers take
    std::vector<chunk_key> shown_keys_;  // the cut the blob holds
};

}  // namespace voxray
