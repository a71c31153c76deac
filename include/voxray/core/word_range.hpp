// A range of 32-bit words inside a structure's blob: what an incremental device
// update copies. Offsets and counts are in words, like every link in a blob.
#pragma once
#include <cstdint>
#include <vector>

namespace voxray {

struct word_range {
    std::uint32_t offset;
    std::uint32_t count;
};

// Adds words [offset, offset + count) to `ranges`, joined to the last range where they
// follow it (for writers that visit their changes in increasing order).
inline void append_joined(std::vector<word_range>& ranges, std::uint32_t offset, std::uint32_t count) {
    if (!ranges.empty() && ranges.back().offset + ranges.back().count == offset) ranges.back().count += count;
    else ranges.push_back({offset, count});
}

}  // namespace voxray
