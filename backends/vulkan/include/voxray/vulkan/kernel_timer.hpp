// Device time of the trace dispatches, from GPU timestamps: what a ray kernel costs on
// the device without the host's copies of rays and hits (which, over PCIe, can take
// longer than the trace itself). Two timestamps bracket the dispatches of one
// submission; both are written at BOTTOM_OF_PIPE, i.e. when all earlier commands of the
// submission (the ray copy) and then the dispatches have finished.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include <vulkan/vulkan.h>

#include "voxray/vulkan/check.hpp"
#include "voxray/vulkan/device.hpp"

namespace voxray::vulkan_detail {

class kernel_timer {
public:
    explicit kernel_timer(const context& ctx) : device_(ctx.device()) {
        std::uint32_t n = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(ctx.physical_device(), &n, nullptr);
        std::vector<VkQueueFamilyProperties> families(n);
        vkGetPhysicalDeviceQueueFamilyProperties(ctx.physical_device(), &n, families.data());
        std::uint32_t bits = ctx.queue_family() < n ? families[ctx.queue_family()].timestampValidBits : 0;
        period_ns_ = ctx.properties().limits.timestampPeriod;
        if (bits == 0 || period_ns_ <= 0) return;  // no timestamps on this queue: seconds() stays NaN
        mask_ = bits >= 64 ? ~std::uint64_t(0) : (std::uint64_t(1) << bits) - 1;
        auto info = vk_struct<VkQueryPoolCreateInfo>(VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO);
        info.queryType = VK_QUERY_TYPE_TIMESTAMP;
        info.queryCount = 2;
        vk_check(vkCreateQueryPool(device_, &info, nullptr, &pool_), "vkCreateQueryPool");
    }
    ~kernel_timer() {
        if (pool_) vkDestroyQueryPool(device_, pool_, nullptr);
    }
    kernel_timer(const kernel_timer&) = delete;
    kernel_timer& operator=(const kernel_timer&) = delete;

    // Around the dispatches of one command buffer.
    void start(VkCommandBuffer cmd) const {
        if (!pool_) return;
        vkCmdResetQueryPool(cmd, pool_, 0, 2);
        vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, 0);
    }
    void stop(VkCommandBuffer cmd) const {
        if (pool_) vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_, 1);
    }

    // Seconds between start and stop of the last submission (after it has completed);
    // NaN where the queue has no timestamps.
    double seconds() const {
        if (!pool_) return NAN;
        std::uint64_t t[2] = {0, 0};
        vk_check(vkGetQueryPoolResults(device_, pool_, 0, 2, sizeof t, t, sizeof t[0],
                                       VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
                 "vkGetQueryPoolResults");
        std::uint64_t ticks = ((t[1] & mask_) - (t[0] & mask_)) & mask_;  // wraps within the valid bits
        return double(ticks) * double(period_ns_) * 1e-9;
    }

private:
    VkDevice device_;
    VkQueryPool pool_ = VK_NULL_HANDLE;
    float period_ns_ = 0;
    std::uint64_t mask_ = 0;
};

}  // namespace voxray::vulkan_detail
