// Packing a commit packet (sync/commit_layout.h) on the host: the table of records and
// the changed words behind it, in one buffer the GPU backends send with one transfer.
// The packer owns a grow-only vector, so a render loop that updates every frame
// allocates nothing once the largest edit has been seen.
#pragma once
#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "voxray/sync/commit_layout.h"
#include "voxray/core/word_range.hpp"
#include "voxray/sync/dirty_ranges.hpp"

namespace voxray::sync {

// Words of a packet for normalized ranges holding `data_words` words in all.
inline std::uint64_t packet_words(std::size_t records, std::uint64_t data_words) {
    return VX_COMMIT_HEADER_WORDS + std::uint64_t(records) * VX_COMMIT_RECORD_WORDS + data_words;
}

class commit_packer {
public:
    // Packs the words of `ranges` (normalized: see normalize_ranges) from `blob`.
    // Returns the packet; it stays valid until the next call.
    std::span<const std::uint32_t> pack(std::span<const std::uint32_t> blob, std::span<const word_range> ranges) {
        std::uint64_t data = total_words(ranges);
        std::uint64_t size = packet_words(ranges.size(), data);
        // resize() never shrinks capacity: the vector is grow-only.
        words_.resize(size);
        std::uint32_t table = VX_COMMIT_HEADER_WORDS;
        std::uint32_t data_offset = table + std::uint32_t(ranges.size()) * VX_COMMIT_RECORD_WORDS;
        words_[VX_COMMIT_HEADER_RECORDS] = std::uint32_t(ranges.size());
        words_[VX_COMMIT_HEADER_DATA_WORDS] = std::uint32_t(data);
        words_[VX_COMMIT_HEADER_TABLE] = table;
        words_[VX_COMMIT_HEADER_DATA] = data_offset;
        std::uint32_t source = 0;
        for (std::size_t r = 0; r < ranges.size(); ++r) {
            std::uint32_t* record = words_.data() + table + r * VX_COMMIT_RECORD_WORDS;
            record[VX_COMMIT_RECORD_DEST] = ranges[r].offset;
            record[VX_COMMIT_RECORD_COUNT] = ranges[r].count;
            record[VX_COMMIT_RECORD_SOURCE] = source;
            std::copy_n(blob.data() + ranges[r].offset, ranges[r].count, words_.data() + data_offset + source);
            source += ranges[r].count;
        }
        return {words_.data(), std::size_t(size)};
    }

    std::size_t capacity_words() const { return words_.capacity(); }

private:
    std::vector<std::uint32_t> words_;
};

}  // namespace voxray::sync
