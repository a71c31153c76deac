// A buffer with its own memory allocation. Storage buffers get device addresses (the
// shaders read them through pointers in push constants); staging buffers are plain
// host memory for copy commands.
//
// Where the host can map device-local memory (lavapipe, integrated GPUs, resizable BAR)
// the engine writes and reads the device buffers directly; elsewhere it copies through
// staging buffers. `mapped()` tells which one a buffer got.
#pragma once
#include <cstdint>
#include <optional>
#include <utility>

#include <vulkan/vulkan.h>

#include "voxray/core/host_code.hpp"
#include "voxray/vulkan/check.hpp"
#include "voxray/vulkan/device.hpp"

namespace voxray::vulkan_detail {

// What the buffer is for; decides usage flags and the memory type sought.
enum class buffer_role {
    storage_upload,    // read by shaders, written by the host (structure, rays)
    storage_readback,  // written by shaders, read by the host (hits)
    staging_upload,    // host-visible source of a copy to a storage buffer
    staging_readback,  // host-visible destination of a copy from a storage buffer
};

inline std::optional<std::uint32_t> find_memory_type(const VkPhysicalDeviceMemoryProperties& memory,
                                                     std::uint32_t allowed, VkMemoryPropertyFlags required) {
    for (std::uint32_t i = 0; i < memory.memoryTypeCount; ++i)
        if ((allowed & (1u << i)) && (memory.memoryTypes[i].propertyFlags & required) == required) return i;
    return std::nullopt;
}

class buffer {
public:
    buffer() = default;

    // Creates a buffer of `size` bytes. `allow_mapped`: a storage buffer may take
    // host-visible device-local memory; false forces plain device-local memory.
    buffer(const context& ctx, VkDeviceSize size, buffer_role role, bool allow_mapped, const char* what);
    ~buffer() { destroy(); }
    buffer(buffer&& o) noexcept { *this = std::move(o); }
    buffer& operator=(buffer&& o) noexcept {
        if (this != &o) {
            destroy();
            device_ = o.device_; buffer_ = o.buffer_; memory_ = o.memory_;
            size_ = o.size_; address_ = o.address_; mapped_ = o.mapped_;
            o.buffer_ = VK_NULL_HANDLE; o.memory_ = VK_NULL_HANDLE; o.mapped_ = nullptr;
        }
        return *this;
    }

    VkBuffer handle() const { return buffer_; }
    VkDeviceSize size() const { return size_; }
    VkDeviceAddress address() const { return address_; }  // 0 for staging buffers
    void* mapped() const { return mapped_; }              // null: reach it with copies

private:
    void create(const context& ctx, buffer_role role, bool allow_mapped, const char* what);

    VkResult allocate(std::uint32_t type, const VkMemoryRequirements& req, bool device_address);

    void destroy() {
        if (!device_) return;
        if (buffer_) vkDestroyBuffer(device_, buffer_, nullptr);
        if (memory_) vkFreeMemory(device_, memory_, nullptr);  // unmaps too
        buffer_ = VK_NULL_HANDLE;
        memory_ = VK_NULL_HANDLE;
        mapped_ = nullptr;
    }

    VkDevice device_ = VK_NULL_HANDLE;
    VkBuffer buffer_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkDeviceSize size_ = 0;
    VkDeviceAddress address_ = 0;
    void* mapped_ = nullptr;
};

}  // namespace voxray::vulkan_detail

// The definitions: here, or compiled once in voxray::kernels (core/host_code.hpp).
#if VOXRAY_HOST_DEFINITIONS
#include "voxray/vulkan/detail/buffer.hpp"
#endif
