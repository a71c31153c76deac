// Incremental updates on Vulkan: the dirty words of a structure blob go to the device in
// one commit packet (sync/commit_layout.h), written once into a host-visible buffer
// (plus one copy command where the device buffer cannot be mapped), and a small compute
// shader (sync/commit.h via shaders/commit.glsl) scatters them into the blob. Cost: the
// changed words plus a small table, whatever the size of the world.
#pragma once
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>

#include <vulkan/vulkan.h>

#include "voxray/core/host_code.hpp"
#include "voxray/core/word_range.hpp"
#include "voxray/sync/commit_packet.hpp"
#include "voxray/vulkan/buffer.hpp"
#include "voxray/vulkan/commands.hpp"
#include "voxray/vulkan/device.hpp"
#include "voxray/vulkan/pipeline.hpp"

namespace voxray::vulkan_detail {

// Must match the push constant block of backends/vulkan/shaders/commit.glsl.
struct commit_push {
    std::uint64_t blob;
    std::uint64_t packet;
    std::uint32_t first;
    std::uint32_t unused;  // pads to the 8-byte alignment of the addresses
};
static_assert(sizeof(commit_push) == 24 && offsetof(commit_push, first) == 16);

// Smallest packet buffer: small edits then never reallocate.
inline constexpr VkDeviceSize min_packet_bytes = 64 * 1024;

class committer {
public:
    // Writes the words of `ranges` (normalized, non-empty) from `blob` into `device_blob`
    // and waits for it. `mapped`: the packet may live in host-visible device memory.
    // Returns the bytes sent.
    std::uint64_t commit(const context& ctx, command_stream& commands, const buffer& device_blob,
                         std::span<const std::uint32_t> blob, std::span<const word_range> ranges, bool mapped);

    // Bytes of device memory the packet buffers hold (grow-only).
    VkDeviceSize capacity() const { return packet_.size(); }

private:
    // Grow-only, in powers of two, so a sequence of growing edits reallocates rarely.
    void reserve(const context& ctx, VkDeviceSize bytes, bool mapped);

    std::unique_ptr<compute_pipeline> pipeline_;
    sync::commit_packer packer_;
    buffer packet_, staging_;
};

}  // namespace voxray::vulkan_detail

// The definitions: here, or compiled once in voxray::kernels (core/host_code.hpp).
#if VOXRAY_HOST_DEFINITIONS
#include "voxray/vulkan/detail/commit.hpp"
#endif
