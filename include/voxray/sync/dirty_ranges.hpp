// Turning a structure's dirty ranges into the set of words an incremental update copies.
// Structures report ranges as they edit: in any order, possibly overlapping, adjacent or
// empty. Every backend first normalizes them here — sorted, merged, checked against the
// blob — so that no word is sent twice, no device work-item races another on the same
// word, and a bad range is an error that names it rather than a write past the buffer.
#pragma once
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/core/word_range.hpp"

namespace voxray::sync {

// Sorted, non-overlapping, non-adjacent, non-empty ranges that cover exactly the words
// of `ranges`. Throws when a range reaches past a blob of `blob_words` words.
inline std::vector<word_range> normalize_ranges(std::span<const word_range> ranges, std::uint64_t blob_words) {
    std::vector<word_range> sorted;
    sorted.reserve(ranges.size());
    for (const word_range& r : ranges) {
        if (std::uint64_t(r.offset) + r.count > blob_words)
            fail("update: dirty range [", r.offset, ", ", std::uint64_t(r.offset) + r.count,
                 ") reaches past the end of the ", blob_words, "-word blob");
        if (r.count > 0) sorted.push_back(r);
    }
    std::sort(sorted.begin(), sorted.end(), [](word_range a, word_range b) { return a.offset < b.offset; });
    std::vector<word_range> merged;
    merged.reserve(sorted.size());
    for (const word_range& r : sorted) {
        // Overlapping or touching the previous range: extend it (ends fit in 32 bits,
        // since they are at most blob_words < 2^31).
        if (!merged.empty() && r.offset <= merged.back().offset + merged.back().count) {
            std::uint32_t end = std::max(merged.back().offset + merged.back().count, r.offset + r.count);
            merged.back().count = end - merged.back().offset;
        } else {
            merged.push_back(r);
        }
    }
    return merged;
}

// Words covered by normalized ranges.
inline std::uint64_t total_words(std::span<const word_range> ranges) {
    std::uint64_t n = 0;
    for (const word_range& r : ranges) n += r.count;
    return n;
}

}  // namespace voxray::sync
