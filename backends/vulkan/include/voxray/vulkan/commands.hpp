// One command buffer, re-recorded for every submission, and the fence the host waits on.
// The engine is synchronous (trace returns with the hits), so one of each is enough.
#pragma once
#include <cstdint>
#include <mutex>

#include <vulkan/vulkan.h>

#include "voxray/core/host_code.hpp"
#include "voxray/vulkan/check.hpp"
#include "voxray/vulkan/device.hpp"

namespace voxray::vulkan_detail {

class command_stream {
public:
    explicit command_stream(const context& ctx);
    ~command_stream() { destroy(); }
    command_stream(const command_stream&) = delete;
    command_stream& operator=(const command_stream&) = delete;

    // Starts recording; the previous submission has completed (submit_and_wait).
    VkCommandBuffer begin();

    // Ends recording, submits, and blocks until the device has finished.
    void submit_and_wait();

    // A memory dependency between two pipeline stages, for all buffers.
    static void barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stage, VkAccessFlags src_access,
                        VkPipelineStageFlags dst_stage, VkAccessFlags dst_access) {
        auto b = vk_struct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
        b.srcAccessMask = src_access;
        b.dstAccessMask = dst_access;
        vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 1, &b, 0, nullptr, 0, nullptr);
    }

private:
    void destroy() {
        if (fence_) vkDestroyFence(device_, fence_, nullptr);
        if (pool_) vkDestroyCommandPool(device_, pool_, nullptr);  // frees the command buffer
        fence_ = VK_NULL_HANDLE;
        pool_ = VK_NULL_HANDLE;
    }

    VkDevice device_;
    VkQueue queue_;
    std::mutex* queue_lock_;
    VkCommandPool pool_ = VK_NULL_HANDLE;
    VkCommandBuffer commands_ = VK_NULL_HANDLE;
    VkFence fence_ = VK_NULL_HANDLE;
};

}  // namespace voxray::vulkan_detail

// The definitions: here, or compiled once in voxray::kernels (core/host_code.hpp).
#if VOXRAY_HOST_DEFINITIONS
#include "voxray/vulkan/detail/commands.hpp"
#endif
