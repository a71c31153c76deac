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
    buffer(const context& ctx, VkDeviceSize size, buffer_role role, bool allow_mapped, const char* what)
        : device_(ctx.device()), size_(size) {
        if (size > ctx.max_buffer() || size > ctx.max_allocation())
            fail("vulkan: ", what, " needs a buffer of ", size, " bytes, above the device's limits (maxBufferSize ",
                 ctx.max_buffer(), ", maxMemoryAllocationSize ", ctx.max_allocation(), ") on ", ctx.name());
        try {
            create(ctx, role, allow_mapped, what);
        } catch (...) {
            destroy();
            throw;
        }
    }
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
    void create(const context& ctx, buffer_role role, bool allow_mapped, const char* what) {
        bool storage = role == buffer_role::storage_upload || role == buffer_role::storage_readback;
        auto info = vk_struct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
        info.size = size_;
        info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
        switch (role) {
        case buffer_role::storage_upload:
            // TRANSFER_SRC too: engine::download_blob copies the blob back (tests, diagnostics).
            info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                         VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
            break;
        case buffer_role::storage_readback:
            info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                         VK_BUFFER_USAGE_TRANSFER_SRC_BIT;
            break;
        case buffer_role::staging_upload: info.usage = VK_BUFFER_USAGE_TRANSFER_SRC_BIT; break;
        case buffer_role::staging_readback: info.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT; break;
        }
        vk_check(vkCreateBuffer(device_, &info, nullptr, &buffer_), "vkCreateBuffer");
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(device_, buffer_, &req);

        // Coherent memory only, so no flush/invalidate calls are needed. The host reads
        // hits, and reading uncached (write-combined) memory is very slow: readback
        // buffers map directly only where the memory is also cached.
        constexpr VkMemoryPropertyFlags host =
            VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        constexpr VkMemoryPropertyFlags local = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;
        constexpr VkMemoryPropertyFlags cached = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
        const auto& mem = ctx.memory();
        std::optional<std::uint32_t> type;
        bool map = true;
        if (role == buffer_role::staging_upload) {
            type = find_memory_type(mem, req.memoryTypeBits, host);
        } else if (role == buffer_role::staging_readback) {
            type = find_memory_type(mem, req.memoryTypeBits, host | cached);
            if (!type) type = find_memory_type(mem, req.memoryTypeBits, host);
        } else {
            VkMemoryPropertyFlags direct = local | host | (role == buffer_role::storage_readback ? cached : 0);
            if (allow_mapped) type = find_memory_type(mem, req.memoryTypeBits, direct);
            // A small BAR heap (256 MiB on many discrete GPUs) may not hold this buffer:
            // then fall back to device-local memory reached by copies.
            if (type && allocate(*type, req, storage) != VK_SUCCESS) type.reset();
            if (!type) {
                map = false;
                type = find_memory_type(mem, req.memoryTypeBits, local);
                if (!type) type = find_memory_type(mem, req.memoryTypeBits, 0);
            }
        }
        if (!type) fail("vulkan: no memory type suits the ", what, " on ", ctx.name());
        if (!memory_) {
            VkDeviceSize heap = mem.memoryHeaps[mem.memoryTypes[*type].heapIndex].size;
            if (req.size > heap)
                fail("vulkan: ", what, " needs ", req.size, " bytes, more than the ", heap, "-byte memory heap of ",
                     ctx.name());
            VkResult r = allocate(*type, req, storage);
            if (r == VK_ERROR_OUT_OF_DEVICE_MEMORY || r == VK_ERROR_OUT_OF_HOST_MEMORY)
                fail("vulkan: out of memory allocating ", req.size, " bytes for the ", what, " (heap of ", heap,
                     " bytes) on ", ctx.name(), ": ", result_name(r));
            vk_check(r, "vkAllocateMemory");
        }
        vk_check(vkBindBufferMemory(device_, buffer_, memory_, 0), "vkBindBufferMemory");
        if (map) vk_check(vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_), "vkMapMemory");
        if (storage) {
            auto address = vk_struct<VkBufferDeviceAddressInfo>(VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO);
            address.buffer = buffer_;
            address_ = vkGetBufferDeviceAddress(device_, &address);
            // The shaders declare 16-byte alignment for rays and hits (vector loads).
            if (address_ == 0 || address_ % 16 != 0)
                fail("vulkan: ", what, " got device address ", address_, ", not 16-byte aligned");
        }
    }

    VkResult allocate(std::uint32_t type, const VkMemoryRequirements& req, bool device_address) {
        auto flags = vk_struct<VkMemoryAllocateFlagsInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO);
        flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
        auto info = vk_struct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO,
                                                    device_address ? &flags : nullptr);
        info.allocationSize = req.size;
        info.memoryTypeIndex = type;
        VkResult r = vkAllocateMemory(device_, &info, nullptr, &memory_);
        if (r != VK_SUCCESS) memory_ = VK_NULL_HANDLE;
        return r;
    }

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
