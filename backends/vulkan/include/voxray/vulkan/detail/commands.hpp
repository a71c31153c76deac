// The command stream's set-up and submission (declared in vulkan/commands.hpp).
#pragma once
#include <cstdint>
#include <mutex>

#include <vulkan/vulkan.h>

#include "voxray/vulkan/check.hpp"
#include "voxray/vulkan/commands.hpp"
#include "voxray/vulkan/device.hpp"

namespace voxray::vulkan_detail {

VOXRAY_HOST_INLINE command_stream::command_stream(const context& ctx)
    : device_(ctx.device()), queue_(ctx.queue()), queue_lock_(&ctx.queue_lock()) {
    try {
        auto pool = vk_struct<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
        pool.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
        pool.queueFamilyIndex = ctx.queue_family();
        vk_check(vkCreateCommandPool(device_, &pool, nullptr, &pool_), "vkCreateCommandPool");
        auto alloc = vk_struct<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
        alloc.commandPool = pool_;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        vk_check(vkAllocateCommandBuffers(device_, &alloc, &commands_), "vkAllocateCommandBuffers");
        auto fence = vk_struct<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
        vk_check(vkCreateFence(device_, &fence, nullptr, &fence_), "vkCreateFence");
    } catch (...) {
        destroy();
        throw;
    }
}

VOXRAY_HOST_INLINE VkCommandBuffer command_stream::begin() {
    vk_check(vkResetCommandBuffer(commands_, 0), "vkResetCommandBuffer");
    auto info = vk_struct<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
    info.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vk_check(vkBeginCommandBuffer(commands_, &info), "vkBeginCommandBuffer");
    return commands_;
}

VOXRAY_HOST_INLINE void command_stream::submit_and_wait() {
    vk_check(vkEndCommandBuffer(commands_), "vkEndCommandBuffer");
    auto submit = vk_struct<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &commands_;
    vk_check(vkResetFences(device_, 1, &fence_), "vkResetFences");
    {
        std::lock_guard guard(*queue_lock_);  // other tracers on this device share the queue
        vk_check(vkQueueSubmit(queue_, 1, &submit, fence_), "vkQueueSubmit");
    }
    // No timeout: a long trace on a slow (CPU) device is legitimate, and a lost
    // device returns VK_ERROR_DEVICE_LOST rather than hanging.
    vk_check(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX), "vkWaitForFences");
}

}  // namespace voxray::vulkan_detail
