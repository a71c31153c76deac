// A buffer's creation and memory (declared in vulkan/buffer.hpp).
#pragma once
#include <cstdint>
#include <optional>

#include <vulkan/vulkan.h>

#include "voxray/core/error.hpp"
#include "voxray/vulkan/buffer.hpp"
#include "voxray/vulkan/check.hpp"
#include "voxray/vulkan/device.hpp"

namespace voxray::vulkan_detail {

VOXRAY_HOST_INLINE buffer::buffer(const context& ctx, VkDeviceSize size, buffer_role role, bool allow_mapped,
                                  const char* what)
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

VOXRAY_HOST_INLINE void buffer::create(const context& ctx, buffer_role role, bool allow_mapped, const char* what) {
    bool storage = role == buffer_role::storage_upload || role == buffer_role::storage_readback;
    auto info = vk_struct<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    info.size = size_;
    info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
    switch (role) {
    case buffer_role::storage_upload:
        // TRANSFER_SRC too: engine::download_blob copies the blob back (tests, diagnostics);
        // INDIRECT_BUFFER: the raster path's draw commands (vulkan/chunk_raster.hpp).
        info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                     VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                     VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT;
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

VOXRAY_HOST_INLINE VkResult buffer::allocate(std::uint32_t type, const VkMemoryRequirements& req, bool device_address) {
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

}  // namespace voxray::vulkan_detail
