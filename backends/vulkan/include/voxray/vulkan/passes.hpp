// Frame passes on Vulkan, for structures registered with PASSES (the chunked world's
// world/frame/passes.h): the structure's <name>_passes module as one pipeline, a frame buffer of
// words that the passes read and write, host access to those words, and one pass run to
// completion. The engine (vulkan/engine.hpp) owns one and lends it the structure blob.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>

#include <vulkan/vulkan.h>

#include "voxray/core/error.hpp"
#include "voxray/vulkan/buffer.hpp"
#include "voxray/vulkan/commands.hpp"
#include "voxray/vulkan/device.hpp"
#include "voxray/vulkan/pipeline.hpp"

namespace voxray::vulkan_detail {

// Must match the push constant block of backends/vulkan/shaders/pass_entry.glsl.
struct pass_push {
    std::uint64_t blob;
    std::uint64_t frame;
    std::uint32_t first;
    std::uint32_t count;
    std::uint32_t pass;
    std::uint32_t unused;  // pads to the 8-byte alignment of the addresses
};
static_assert(sizeof(pass_push) == 32 && offsetof(pass_push, first) == 16 && offsetof(pass_push, pass) == 24);

class pass_runner {
public:
    // The world's frame passes keep the nearest hit by a 64-bit atomic max; other pass
    // programs (the mesher kernel) need no 64-bit atomics.
    explicit pass_runner(bool needs_int64_atomics = true) : needs_int64_atomics_(needs_int64_atomics) {}

    // Room for `words` frame words (grow-only; growing drops the old contents).
    void reserve(const context& ctx, std::size_t words) {
        VkDeviceSize bytes = std::max<VkDeviceSize>(VkDeviceSize(words) * 4, 8);
        if (frame_.handle() && frame_.size() >= bytes) return;
        frame_ = buffer();
        frame_ = buffer(ctx, bytes, buffer_role::storage_upload, true, "frame buffer");
    }

    void write(const context& ctx, command_stream& commands, std::size_t at, std::span<const std::uint32_t> words) {
        check_range(at, words.size());
        if (words.empty()) return;
        if (frame_.mapped()) {
            std::memcpy(static_cast<std::uint32_t*>(frame_.mapped()) + at, words.data(), words.size_bytes());
            return;  // host writes before vkQueueSubmit are visible to the device
        }
        buffer staging(ctx, words.size_bytes(), buffer_role::staging_upload, true, "frame staging buffer");
        std::memcpy(staging.mapped(), words.data(), words.size_bytes());
        VkCommandBuffer cmd = commands.begin();
        VkBufferCopy region{0, VkDeviceSize(at) * 4, words.size_bytes()};
        vkCmdCopyBuffer(cmd, staging.handle(), frame_.handle(), 1, &region);
        command_stream::barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        commands.submit_and_wait();
    }

    // Every pass ends with a barrier to host reads (run), so mapped words are current here.
    void read(const context& ctx, command_stream& commands, std::size_t at, std::span<std::uint32_t> words) {
        check_range(at, words.size());
        if (words.empty()) return;
        if (frame_.mapped()) {
            std::memcpy(words.data(), static_cast<const std::uint32_t*>(frame_.mapped()) + at, words.size_bytes());
            return;
        }
        buffer staging(ctx, words.size_bytes(), buffer_role::staging_readback, true, "frame read-back");
        VkCommandBuffer cmd = commands.begin();
        VkBufferCopy region{VkDeviceSize(at) * 4, 0, words.size_bytes()};
        vkCmdCopyBuffer(cmd, frame_.handle(), staging.handle(), 1, &region);
        command_stream::barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
        commands.submit_and_wait();
        std::memcpy(words.data(), staging.mapped(), words.size_bytes());
    }

    // Runs `count` items of pass `pass` over the blob at `blob` and waits for them.
    void run(const context& ctx, command_stream& commands, std::span<const std::uint32_t> spirv, VkDeviceAddress blob,
             std::uint32_t pass, std::uint64_t count) {
        if (!frame_.handle()) fail("vulkan: a frame pass ran before the frame buffer was reserved");
        if (!pipeline_) {
            if (needs_int64_atomics_ && !ctx.int64_atomics())
                fail("vulkan: the frame passes need 64-bit buffer atomics (shaderInt64 and shaderBufferInt64Atomics), "
                     "which ", ctx.owns_device() ? "the device " + ctx.name() + " lacks"
                                                 : std::string("voxray cannot confirm on the application's device"));
            pipeline_ = std::make_unique<compute_pipeline>(ctx, spirv, std::uint32_t(sizeof(pass_push)));
        }
        VkCommandBuffer cmd = commands.begin();
        std::uint64_t per = std::uint64_t(ctx.properties().limits.maxComputeWorkGroupCount[0]) * group_size;
        for (std::uint64_t first = 0; first < count; first += per) {
            std::uint64_t n = std::min(per, count - first);
            pass_push pc{blob, frame_.address(), std::uint32_t(first), std::uint32_t(n), pass, 0};
            pipeline_->bind(cmd, pc);
            vkCmdDispatch(cmd, std::uint32_t((n + group_size - 1) / group_size), 1, 1);
            // Each dispatch's atomics and writes before the next one's reads.
            command_stream::barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                                    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_HOST_BIT |
                                        VK_PIPELINE_STAGE_TRANSFER_BIT,
                                    VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_HOST_READ_BIT |
                                        VK_ACCESS_TRANSFER_READ_BIT);
        }
        commands.submit_and_wait();
    }

    VkDeviceSize bytes() const { return frame_.handle() ? frame_.size() : 0; }
    VkDeviceAddress address() const { return frame_.handle() ? frame_.address() : 0; }

private:
    void check_range(std::size_t at, std::size_t n) const {
        if (VkDeviceSize(at + n) * 4 > bytes())
            fail("vulkan: frame words [", at, ", ", at + n, ") outside the frame buffer's ", bytes() / 4, " words");
    }

    bool needs_int64_atomics_;
    std::unique_ptr<compute_pipeline> pipeline_;
    buffer frame_;
};

}  // namespace voxray::vulkan_detail
