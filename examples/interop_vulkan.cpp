// voxray inside an application that owns its Vulkan device: the application creates the
// instance, device, queue and a ray/hit buffer; voxray borrows them (vulkan_options::
// user_device) and records its trace into the application's command buffer, between the
// application's own barriers. Nothing goes through host memory but the rays written and the
// hits read here for the demonstration (a renderer would write and read them in shaders).
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "voxray/naadf/naadf.hpp"
#include "voxray/vulkan.hpp"

namespace {

void ok(VkResult r, const char* call) {
    if (r != VK_SUCCESS) voxray::fail(call, " failed: ", int(r));
}

template <class T>
T zeroed(VkStructureType type, void* next = nullptr) {
    T s{};
    s.sType = type;
    s.pNext = next;
    return s;
}

void barrier(VkCommandBuffer cmd, VkPipelineStageFlags src_stage, VkAccessFlags src, VkPipelineStageFlags dst_stage,
             VkAccessFlags dst) {
    auto b = zeroed<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
    b.srcAccessMask = src;
    b.dstAccessMask = dst;
    vkCmdPipelineBarrier(cmd, src_stage, dst_stage, 0, 1, &b, 0, nullptr, 0, nullptr);
}

}  // namespace

int main() try {
    // --- The application's device (Vulkan 1.2, bufferDeviceAddress enabled). ---
    auto app = zeroed<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.apiVersion = VK_API_VERSION_1_2;
    auto instance_info = zeroed<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    instance_info.pApplicationInfo = &app;
    VkInstance instance;
    ok(vkCreateInstance(&instance_info, nullptr, &instance), "vkCreateInstance");
    std::uint32_t n = 1;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    vkEnumeratePhysicalDevices(instance, &n, &physical);
    if (!physical) voxray::fail("no Vulkan device");
    std::uint32_t family = 0;  // queue family 0 has compute on every common driver; a renderer checks
    float priority = 1.0f;
    auto queue_info = zeroed<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queue_info.queueFamilyIndex = family;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    auto v12 = zeroed<VkPhysicalDeviceVulkan12Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
    v12.bufferDeviceAddress = VK_TRUE;
    auto device_info = zeroed<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &v12);
    device_info.queueCreateInfoCount = 1;
    device_info.pQueueCreateInfos = &queue_info;
    VkDevice device;
    ok(vkCreateDevice(physical, &device_info, nullptr, &device), "vkCreateDevice");
    VkQueue queue;
    vkGetDeviceQueue(device, family, 0, &queue);

    // --- One buffer holding rays, then hits (offsets are multiples of 16). ---
    constexpr std::uint32_t w = 64, count = w * w;
    constexpr VkDeviceSize ray_offset = 0, hit_offset = count * sizeof(voxray::ray);
    auto buffer_info = zeroed<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
    buffer_info.size = 2 * hit_offset;
    buffer_info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT;
    VkBuffer buffer;
    ok(vkCreateBuffer(device, &buffer_info, nullptr, &buffer), "vkCreateBuffer");
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device, buffer, &req);
    VkPhysicalDeviceMemoryProperties memory;
    vkGetPhysicalDeviceMemoryProperties(physical, &memory);
    constexpr VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
    std::uint32_t type = 0;
    while (type < memory.memoryTypeCount &&
           !((req.memoryTypeBits >> type & 1) && (memory.memoryTypes[type].propertyFlags & host) == host))
        ++type;
    auto flags = zeroed<VkMemoryAllocateFlagsInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO);
    flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
    auto alloc = zeroed<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, &flags);
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex = type;
    VkDeviceMemory buffer_memory;
    ok(vkAllocateMemory(device, &alloc, nullptr, &buffer_memory), "vkAllocateMemory");
    ok(vkBindBufferMemory(device, buffer, buffer_memory, 0), "vkBindBufferMemory");
    void* mapped;
    ok(vkMapMemory(device, buffer_memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
    auto* bytes = static_cast<unsigned char*>(mapped);

    // Rays straight down onto a sphere; here the host writes them, a renderer's shader would.
    std::vector<voxray::ray> rays;
    for (std::uint32_t y = 0; y < w; ++y)
        for (std::uint32_t x = 0; x < w; ++x)
            rays.push_back({{float(x) / 2 + 0.25f, 40.0f, float(y) / 2 + 0.25f}, 0.0f, {0, -1, 0}, INFINITY});
    std::memcpy(bytes + ray_offset, rays.data(), count * sizeof(voxray::ray));

    {
        voxray::voxel_model model;
        for (int z = 0; z < 32; ++z)  // a ball of radius 12 around (16, 16, 16)
            for (int y = 0; y < 32; ++y)
                for (int x = 0; x < 32; ++x)
                    if ((x - 16) * (x - 16) + (y - 16) * (y - 16) + (z - 16) * (z - 16) <= 144) model.set({x, y, z}, 1);
        voxray::naadf world(model);
        voxray::vulkan_options options;
        options.user_device = voxray::vulkan_user_device{instance, physical, device, family, queue};
        voxray::tracer<voxray::vulkan, voxray::naadf> tracer(world, options);

        // --- The application's frame: its command buffer, voxray's dispatches inside. ---
        auto pool_info = zeroed<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
        pool_info.queueFamilyIndex = family;
        VkCommandPool pool;
        ok(vkCreateCommandPool(device, &pool_info, nullptr, &pool), "vkCreateCommandPool");
        auto cmd_info = zeroed<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
        cmd_info.commandPool = pool;
        cmd_info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        cmd_info.commandBufferCount = 1;
        VkCommandBuffer cmd;
        ok(vkAllocateCommandBuffers(device, &cmd_info, &cmd), "vkAllocateCommandBuffers");
        auto begin = zeroed<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
        ok(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
        // (A renderer's ray-generation pass would go here, then this barrier.)
        barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
        tracer.record_closest_hit(cmd, voxray::vulkan_buffer_range{buffer, ray_offset},
                                  voxray::vulkan_buffer_range{buffer, hit_offset}, count);
        // (A shading pass would read the hits after a COMPUTE -> COMPUTE barrier; here the host does.)
        barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT, VK_PIPELINE_STAGE_HOST_BIT,
                VK_ACCESS_HOST_READ_BIT);
        ok(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
        auto submit = zeroed<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd;
        ok(vkQueueSubmit(queue, 1, &submit, VK_NULL_HANDLE), "vkQueueSubmit");
        ok(vkQueueWaitIdle(queue), "vkQueueWaitIdle");  // the recording must finish before the tracer goes
        vkDestroyCommandPool(device, pool, nullptr);
    }  // the tracer is gone; the device is still the application's

    std::vector<voxray::hit> hits(count);
    std::memcpy(hits.data(), bytes + hit_offset, count * sizeof(voxray::hit));
    std::uint32_t hit_count = 0;
    for (const voxray::hit& h : hits) hit_count += h.is_hit();
    const voxray::hit& centre = hits[(w / 2) * w + w / 2];  // ray at x = z = 16.25
    std::printf("%u of %u rays hit; centre: t=%.2f voxel=(%d,%d,%d) face=%s\n", hit_count, count, centre.t,
                centre.voxel.x, centre.voxel.y, centre.voxel.z, voxray::face_name(centre.normal));

    vkDestroyBuffer(device, buffer, nullptr);
    vkFreeMemory(device, buffer_memory, nullptr);
    vkDestroyDevice(device, nullptr);
    vkDestroyInstance(instance, nullptr);
    return centre.is_hit() && hit_count > 0 && hit_count < count ? 0 : 1;
} catch (const voxray::error& e) {
    std::fprintf(stderr, "interop_vulkan: %s\n", e.what());
    return 1;
}
