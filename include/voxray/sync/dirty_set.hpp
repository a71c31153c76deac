// What changed in a structure's blob since the last take: whole bricks (by index, the
// brickmap's unit), single words (cells and page-table entries, by word offset), ranges
// of words (NAADF's arrays and groups), or "everything" after the blob was re-laid out
// (growth, build, load). take() turns that into sorted,
// coalesced word ranges for an incremental device update.
//
// Plain data: the structure guards it (the brickmap: a mutex for additions during edits; takes happen
// under its exclusive lock). Bricks are de-duplicated by a flag in the brick's metadata,
// words by sorting at take time.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "voxray/core/word_range.hpp"

namespace voxray {

class dirty_set {
public:
    // Ranges closer than this many words are merged: one copy beats two tiny ones.
    static constexpr std::uint32_t merge_gap = 8;

    void add_brick(std::uint32_t brick) { bricks_.push_back(brick); }
    void add_word(std::uint32_t offset) { words_.push_back(offset); }
    void add_bricks(const std::vector<std::uint32_t>& b) { bricks_.insert(bricks_.end(), b.begin(), b.end()); }
    void add_words(const std::vector<std::uint32_t>& w) { words_.insert(words_.end(), w.begin(), w.end()); }
    void add_range(word_range r) { ranges_.push_back(r); }
    void mark_whole() { whole_ = true; }

    bool whole() const { return whole_; }
    bool empty() const { return !whole_ && bricks_.empty() && words_.empty() && ranges_.empty(); }
    const std::vector<std::uint32_t>& bricks() const { return bricks_; }

    // Coalesced ranges; {0, blob_words} alone when the whole blob is dirty. Clears the set.
    std::vector<word_range> take(std::uint32_t blob_words, std::uint32_t bricks_offset, std::uint32_t brick_words) {
        std::vector<word_range> out;
        if (whole_) {
            if (blob_words) out.push_back({0, blob_words});
        } else {
            std::vector<word_range> parts;
            parts.reserve(bricks_.size() + words_.size() + ranges_.size());
            parts.insert(parts.end(), ranges_.begin(), ranges_.end());
            for (auto b : bricks_) parts.push_back({bricks_offset + b * brick_words, brick_words});
            for (auto w : words_) parts.push_back({w, 1});
            std::sort(parts.begin(), parts.end(), [](auto& a, auto& b) { return a.offset < b.offset; });
            for (auto& p : parts) {
                if (!out.empty() && p.offset <= out.back().offset + out.back().count + merge_gap) {
                    std::uint32_t end = std::max(out.back().offset + out.back().count, p.offset + p.count);
                    out.back().count = end - out.back().offset;
                } else {
                    out.push_back(p);
                }
            }
        }
        clear();
        return out;
    }
    void clear() {
        whole_ = false;
        bricks_.clear();
        words_.clear();
        ranges_.clear();
    }

private:
    std::vector<std::uint32_t> bricks_;
    std::vector<std::uint32_t> words_;
    std::vector<word_range> ranges_;
    bool whole_ = false;
};

}  // namespace voxray
