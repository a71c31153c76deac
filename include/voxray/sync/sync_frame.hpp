// What an editable structure hands a consumer (a tracer, save()) while other threads may
// edit: a consistent view of its blob. Writers wait (the exclusive lock is held) for as
// long as the frame lives, so upload or copy what you need and let it go. `ranges`: the
// words changed after the generation asked for (the whole blob when it was re-laid out
// since); `generation`: what to ask for next time; `voxels`: the solid voxel count.
#pragma once
#include <cstdint>
#include <mutex>
#include <shared_mutex>
#include <span>
#include <vector>

#include "voxray/core/word_range.hpp"

namespace voxray {

struct sync_frame {
    std::unique_lock<std::shared_mutex> lock;
    std::span<const std::uint32_t> blob;
    std::vector<word_range> ranges;
    std::uint64_t generation = 0;
    std::uint64_t voxels = 0;
};

}  // namespace voxray
