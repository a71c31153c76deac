// Interop: voxray on the application's own Vulkan device, tracing rays that are already
// in the application's buffers.
//
//   vulkan_user_device   the handles voxray borrows (vulkan_options::user_device). voxray
//                        never destroys them; they must outlive every tracer made on them.
//   vulkan_buffer_range  rays or hits in a VkBuffer the application owns.
//
// Requirements on the application's side (voxray checks what it can, and says which one
// failed; the rest is undefined behaviour, as everywhere in Vulkan):
//   - instance created with apiVersion >= 1.2; physical device with Vulkan 1.2;
//   - device created with VkPhysicalDeviceVulkan12Features::bufferDeviceAddress enabled;
//   - queue from `queue_family`, which supports compute; voxray submits its uploads (and
//     the waiting trace) to it, so calls into voxray must not overlap other threads'
//     vkQueueSubmit on that queue (Vulkan's external synchronisation rule);
//   - ray and hit buffers created with VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
//     VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT, bound to memory allocated with
//     VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT; offsets multiples of 16.
//
// Synchronisation, two ways to trace (tracer::closest_hit / any_hit, and record_*):
//   t.closest_hit(rays, hits, count)       one submission on the queue, waited on. A
//       barrier before it makes the writes of earlier work on that queue (the rays)
//       visible; one after makes the hits visible to later work on the queue and to the host.
//   t.record_closest_hit(cmd, rays, hits, count)   records into the application's command
//       buffer (recording, for a queue of `queue_family`) and submits nothing. It binds
//       voxray's compute pipeline and push constants (rebind yours after) and records no
//       barrier: the application orders its ray writes before it (dst COMPUTE_SHADER /
//       SHADER_READ; also SHADER_WRITE if earlier work used the hit buffer) and its hit
//       reads after it (src COMPUTE_SHADER / SHADER_WRITE). The recording uses the
//       tracer's structure buffer as it is now: it must finish executing before update()
//       or the tracer's destruction, and be recorded anew after update().
// Structure uploads and update() run on the same queue and wait, as without interop.
//
// Layout: both buffers hold `count` records of 32 bytes, exactly core/ray_hit_layout.h
// (vx_ray: origin, tmin, direction, tmax; vx_hit: t, voxel, face, material, steps,
// status), i.e. voxray::ray and voxray::hit as bytes. Hit i belongs to ray i.
#pragma once
#include <cstddef>
#include <cstdint>

#include <vulkan/vulkan.h>

#include "voxray/core/ray_hit_layout.h"
#include "voxray/vulkan/check.hpp"

namespace voxray {

struct vulkan_user_device {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical_device = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    std::uint32_t queue_family = 0;
    VkQueue queue = VK_NULL_HANDLE;
};

// `size`: bytes usable from `offset`; VK_WHOLE_SIZE when the caller does not say (voxray
// then checks against the buffer's memory requirements only, an upper bound).
struct vulkan_buffer_range {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceSize offset = 0;
    VkDeviceSize size = VK_WHOLE_SIZE;
};

namespace vulkan_detail {

// The device address of `count` 32-byte records in `range`, after checking what can be
// checked; `what` ("rays", "hits") names the argument in errors.
inline VkDeviceAddress record_address(VkDevice device, const vulkan_buffer_range& range, std::size_t count,
                                      const char* what) {
    if (!range.buffer) fail("vulkan: the ", what, " buffer is VK_NULL_HANDLE");
    if (range.offset % 16 != 0)
        fail("vulkan: the ", what, " offset is ", range.offset, " bytes; it must be a multiple of 16");
    VkDeviceSize bytes = VkDeviceSize(count) * VX_RAY_BYTES;
    if (range.size != VK_WHOLE_SIZE && bytes > range.size)
        fail("vulkan: ", count, " ", what, " need ", bytes, " bytes, but the ", what, " range holds ", range.size);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device, range.buffer, &req);
    if (range.offset > req.size || bytes > req.size - range.offset)
        fail("vulkan: ", count, " ", what, " at offset ", range.offset, " need ", bytes, " bytes, past the end of the ",
             what, " buffer (", req.size, " bytes)");
    auto info = vk_struct<VkBufferDeviceAddressInfo>(VK_STRUCTURE_TYPE_BUFFER_DEVICE_ADDRESS_INFO);
    info.buffer = range.buffer;
    VkDeviceAddress base = vkGetBufferDeviceAddress(device, &info);
    if (base == 0)
        fail("vulkan: the ", what, " buffer has no device address: create it with "
             "VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT and its memory with VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT");
    if (base % 16 != 0) fail("vulkan: the ", what, " buffer's device address ", base, " is not 16-byte aligned");
    return base + range.offset;
}

}  // namespace vulkan_detail
}  // namespace voxray
