// Which blob words changed in which generation, so that every consumer of one structure
// (a tracer per backend, a tool's own copy) asks "what changed since generation g" and
// gets just that, however many consumers there are and whenever they were made.
//
//   generation:   1 (whole)   2          3         4 (whole: growth)   5
//   entries:      -           [a, b)     [c, d)    -                   [e, f)
//   changes_since(3) = whole blob (4 re-laid it out); changes_since(4) = [e, f)
//
// The log keeps ranges covering at most the blob's size (past that, sending the whole
// blob is as cheap) in at most blob words / 16 entries (16 bytes each: a quarter of the
// blob's memory); dropping the oldest entries makes older consumers get the whole blob,
// never too little. Plain data: the structure commits and reads it under its
// exclusive lock.
#pragma once
#include <algorithm>
#include <cstdint>
#include <deque>
#include <vector>

#include "voxray/sync/dirty_set.hpp"
#include "voxray/core/word_range.hpp"
#include "voxray/sync/dirty_ranges.hpp"

namespace voxray {

class change_log {
public:
    std::uint64_t generation() const { return generation_; }

    // Moves the dirty set into the log as a new generation (nothing when it is empty).
    void commit(dirty_set& dirty, std::uint32_t blob_words, std::uint32_t bricks_offset, std::uint32_t brick_words) {
        if (dirty.empty()) return;
        bool whole = dirty.whole();
        commit(dirty.take(blob_words, bricks_offset, brick_words), whole, blob_words);
    }

    // The same for a structure that collects its own ranges: `whole` when the blob was
    // re-laid out (then the ranges are not kept). Nothing when there is nothing to log.
    void commit(const std::vector<word_range>& ranges, bool whole, std::uint32_t blob_words) {
        if (ranges.empty() && !whole) return;
        ++generation_;
        if (whole) {
            entries_.clear();
            logged_words_ = 0;
            whole_at_ = generation_;
            return;
        }
        for (const word_range& r : ranges) {
            entries_.push_back({generation_, r});
            logged_words_ += r.count;
        }
        const std::size_t max_entries = std::max<std::size_t>(1024, blob_words / 16);
        while ((logged_words_ > blob_words || entries_.size() > max_entries) && !entries_.empty()) {
            lost_at_ = std::max(lost_at_, entries_.front().generation);
            logged_words_ -= entries_.front().range.count;
            entries_.pop_front();
        }
    }

    // The words changed after generation g, sorted and coalesced; {0, blob_words} alone
    // when the whole blob changed since (or g is older than what the log still holds).
    std::vector<word_range> since(std::uint64_t g, std::uint32_t blob_words) const {
        if (whole_since(g)) return {{0, blob_words}};
        std::vector<word_range> parts;
        auto first = std::partition_point(entries_.begin(), entries_.end(),
                                          [&](const entry& e) { return e.generation <= g; });
        for (auto it = first; it != entries_.end(); ++it) parts.push_back(it->range);
        return sync::normalize_ranges(parts, blob_words);
    }

    bool whole_since(std::uint64_t g) const { return g < std::max(whole_at_, lost_at_); }

private:
    struct entry {
        std::uint64_t generation;
        word_range range;
    };
    std::deque<entry> entries_;  // generations ascending
    std::uint64_t generation_ = 0, whole_at_ = 0, lost_at_ = 0, logged_words_ = 0;
};

}  // namespace voxray
