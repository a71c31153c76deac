// The commit packet's upload and scatter (declared in vulkan/commit.hpp).
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>

#include <vulkan/vulkan.h>

#include "voxray/generated/spirv_commit.hpp"
#include "voxray/vulkan/commit.hpp"

namespace voxray::vulkan_detail {

VOXRAY_HOST_INLINE std::uint64_t committer::commit(const context& ctx, command_stream& commands,
                                                   const buffer& device_blob, std::span<const std::uint32_t> blob,
                                                   std::span<const word_range> ranges, bool mapped) {
    // Created on first use: tracers that never edit pay no pipeline compile.
    if (!pipeline_)
        pipeline_ = std::make_unique<compute_pipeline>(ctx, std::span<const std::uint32_t>(voxray_spirv_commit),
                                                       std::uint32_t(sizeof(commit_push)));
    std::span<const std::uint32_t> packet = packer_.pack(blob, ranges);
    VkDeviceSize bytes = packet.size_bytes();
    reserve(ctx, bytes, mapped);
    std::memcpy(packet_.mapped() ? packet_.mapped() : staging_.mapped(), packet.data(), bytes);

    VkCommandBuffer cmd = commands.begin();
    if (!packet_.mapped()) {
        VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, staging_.handle(), packet_.handle(), 1, &region);
    }
    // The packet copy (if any) and any staged blob upload before it land before the
    // shader reads the packet and writes the blob.
    command_stream::barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                            VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
    std::uint64_t words = packet[VX_COMMIT_HEADER_DATA_WORDS];
    std::uint64_t max_groups = ctx.properties().limits.maxComputeWorkGroupCount[0];
    std::uint64_t per_dispatch = max_groups * group_size;
    for (std::uint64_t first = 0; first < words; first += per_dispatch) {
        std::uint64_t n = std::min(per_dispatch, words - first);
        commit_push pc{device_blob.address(), packet_.address(), std::uint32_t(first), 0};
        pipeline_->bind(cmd, pc);
        vkCmdDispatch(cmd, std::uint32_t((n + group_size - 1) / group_size), 1, 1);
    }
    // Shader writes to the blob before anything that follows: the next trace (shader
    // read), a full upload (transfer or host write), a read-back (transfer or host read).
    command_stream::barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                            VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                                VK_PIPELINE_STAGE_HOST_BIT,
                            VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT |
                                VK_ACCESS_TRANSFER_WRITE_BIT | VK_ACCESS_HOST_READ_BIT |
                                VK_ACCESS_HOST_WRITE_BIT);
    commands.submit_and_wait();
    return bytes;
}

VOXRAY_HOST_INLINE void committer::reserve(const context& ctx, VkDeviceSize bytes, bool mapped) {
    if (packet_.handle() && packet_.size() >= bytes) return;
    VkDeviceSize size = std::max(min_packet_bytes, std::bit_ceil(bytes));
    size = std::max(bytes, std::min({size, ctx.max_buffer(), ctx.max_allocation()}));
    packet_ = buffer();  // free the old ones first: old and new may not both fit
    staging_ = buffer();
    packet_ = buffer(ctx, size, buffer_role::storage_upload, mapped, "commit packet");
    if (!packet_.mapped()) {
        try {
            staging_ = buffer(ctx, size, buffer_role::staging_upload, true, "commit staging buffer");
        } catch (...) {
            packet_ = buffer();  // all or nothing
            throw;
        }
    }
}

}  // namespace voxray::vulkan_detail
