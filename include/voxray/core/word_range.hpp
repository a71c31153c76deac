// A range of 32-bit words inside a structure's blob: what an incremental device
// update copies. Offsets and counts are in words, like every link in a blob.
#pragma once
#include <cstdint>

namespace voxray {

struct word_range {
    std::uint32_t offset;
    std::uint32_t count;
};

}  // namespace voxray
