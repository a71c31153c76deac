// Device selection and the context's set-up (declared in vulkan/device.hpp).
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "voxray/core/error.hpp"
#include "voxray/vulkan/check.hpp"
#include "voxray/vulkan/device.hpp"

namespace voxray::vulkan_detail {

VOXRAY_HOST_INLINE std::vector<VkExtensionProperties> device_extensions(VkPhysicalDevice pd) {
    std::uint32_t n = 0;
    vk_check(vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr), "vkEnumerateDeviceExtensionProperties");
    std::vector<VkExtensionProperties> list(n);
    vk_check(vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, list.data()),
             "vkEnumerateDeviceExtensionProperties");
    list.resize(n);
    return list;
}

VOXRAY_HOST_INLINE candidate inspect(VkPhysicalDevice pd) {
    candidate c;
    c.handle = pd;
    vkGetPhysicalDeviceProperties(pd, &c.properties);
    if (c.properties.apiVersion < required_api) {
        c.problem = "supports Vulkan " + version_string(c.properties.apiVersion) + ", needs 1.2";
        return c;
    }
    auto v12 = vk_struct<VkPhysicalDeviceVulkan12Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
    auto features = vk_struct<VkPhysicalDeviceFeatures2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &v12);
    vkGetPhysicalDeviceFeatures2(pd, &features);
    if (!v12.bufferDeviceAddress) {
        c.problem = "lacks the bufferDeviceAddress feature";
        return c;
    }
    c.int64_atomics = features.features.shaderInt64 && v12.shaderBufferInt64Atomics;
    std::uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(pd, &n, families.data());
    // A family that computes and draws where there is one (the raster path needs both on
    // its queue), else any that computes.
    auto with = [&](VkQueueFlags flags) {
        return std::find_if(families.begin(), families.end(), [&](const VkQueueFamilyProperties& f) {
            return (f.queueFlags & flags) == flags && f.queueCount > 0;
        });
    };
    auto compute = with(VK_QUEUE_COMPUTE_BIT | VK_QUEUE_GRAPHICS_BIT);
    if (compute == families.end()) compute = with(VK_QUEUE_COMPUTE_BIT);
    if (compute == families.end()) {
        c.problem = "has no compute queue";
        return c;
    }
    c.queue_family = std::uint32_t(compute - families.begin());
    c.graphics = (compute->queueFlags & VK_QUEUE_GRAPHICS_BIT) != 0;
    c.indirect_draws = features.features.multiDrawIndirect && features.features.drawIndirectFirstInstance;
    // The spec requires enabling VK_KHR_portability_subset where it exists (MoltenVK).
    c.portability_subset = has_extension(device_extensions(pd), "VK_KHR_portability_subset");
    return c;
}

VOXRAY_HOST_INLINE void instance::create() {
    // vkEnumerateInstanceVersion is missing from 1.0 loaders, which cannot do 1.2 anyway.
    auto enumerate_version = reinterpret_cast<PFN_vkEnumerateInstanceVersion>(
        vkGetInstanceProcAddr(nullptr, "vkEnumerateInstanceVersion"));
    std::uint32_t loader = VK_API_VERSION_1_0;
    if (enumerate_version) vk_check(enumerate_version(&loader), "vkEnumerateInstanceVersion");
    if (loader < required_api)
        fail("vulkan: the Vulkan loader supports API ", version_string(loader), ", voxray needs 1.2");
    std::uint32_t n = 0;
    vk_check(vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr),
             "vkEnumerateInstanceExtensionProperties");
    std::vector<VkExtensionProperties> available(n);
    vk_check(vkEnumerateInstanceExtensionProperties(nullptr, &n, available.data()),
             "vkEnumerateInstanceExtensionProperties");
    available.resize(n);
    auto app = vk_struct<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
    app.pApplicationName = "voxray";
    app.pEngineName = "voxray";
    app.apiVersion = required_api;
    auto info = vk_struct<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
    info.pApplicationInfo = &app;
#ifdef VK_KHR_portability_enumeration
    // Lists portability drivers (MoltenVK) too; without it they are hidden.
    const char* portability = VK_KHR_PORTABILITY_ENUMERATION_EXTENSION_NAME;
    if (has_extension(available, portability)) {
        info.flags |= VK_INSTANCE_CREATE_ENUMERATE_PORTABILITY_BIT_KHR;
        info.enabledExtensionCount = 1;
        info.ppEnabledExtensionNames = &portability;
    }
#endif
    VkResult r = vkCreateInstance(&info, nullptr, &handle_);
    // The loader's answer when it finds no driver (ICD) at all.
    if (r == VK_ERROR_INCOMPATIBLE_DRIVER)
        fail("vulkan: vkCreateInstance failed: VK_ERROR_INCOMPATIBLE_DRIVER: no Vulkan 1.2 driver found; "
             "install one (for a CPU device, Mesa's lavapipe: Debian package mesa-vulkan-drivers)");
    vk_check(r, "vkCreateInstance");
}

VOXRAY_HOST_INLINE candidate choose_device(VkInstance inst, const vulkan_options& options) {
    std::uint32_t n = 0;
    vk_check(vkEnumeratePhysicalDevices(inst, &n, nullptr), "vkEnumeratePhysicalDevices");
    std::vector<VkPhysicalDevice> devices(n);
    vk_check(vkEnumeratePhysicalDevices(inst, &n, devices.data()), "vkEnumeratePhysicalDevices");
    devices.resize(n);
    if (devices.empty())
        fail("vulkan: no Vulkan device found: install a driver (for a CPU device, Mesa's lavapipe: "
             "Debian package mesa-vulkan-drivers)");

    std::string wanted = options.device, source = "vulkan_options::device";
    if (wanted.empty()) {
        if (const char* env = std::getenv("VOXRAY_VULKAN_DEVICE"); env && *env) {
            wanted = env;
            source = "VOXRAY_VULKAN_DEVICE";
        }
    }
    std::vector<candidate> all;
    for (VkPhysicalDevice pd : devices) all.push_back(inspect(pd));

    const candidate* best = nullptr;
    std::string seen;
    for (const candidate& c : all) {
        std::string name = c.properties.deviceName;
        seen += "\n  " + name + (c.problem.empty() ? "" : " (" + c.problem + ")");
        if (!wanted.empty() && name.find(wanted) == std::string::npos) continue;
        if (!c.problem.empty()) continue;
        if (!best || type_rank(c.properties.deviceType) < type_rank(best->properties.deviceType)) best = &c;
    }
    if (!best) {
        if (!wanted.empty())
            fail("vulkan: no usable device whose name contains \"", wanted, "\" (from ", source,
                 "); devices:", seen);
        fail("vulkan: no usable device (voxray needs Vulkan 1.2 with bufferDeviceAddress and a compute queue); "
             "devices:", seen);
    }
    return *best;
}

VOXRAY_HOST_INLINE context::context(std::shared_ptr<const instance> inst, const candidate& chosen)
    : instance_(std::move(inst)), chosen_(chosen) {
    try {
        vkGetPhysicalDeviceMemoryProperties(chosen_.handle, &memory_);
        read_limits();
        create_device();
    } catch (...) {
        destroy();
        throw;
    }
}

VOXRAY_HOST_INLINE void context::borrow(const vulkan_user_device& user) {
    auto missing = [](const char* field) {
        fail("vulkan: vulkan_user_device::", field, " is VK_NULL_HANDLE; voxray needs all of instance, "
             "physical_device, device and queue");
    };
    if (!user.instance) missing("instance");
    if (!user.physical_device) missing("physical_device");
    if (!user.device) missing("device");
    if (!user.queue) missing("queue");
    chosen_ = inspect(user.physical_device);
    if (!chosen_.problem.empty())
        fail("vulkan: the application's device ", chosen_.properties.deviceName, " ", chosen_.problem);
    std::uint32_t n = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(user.physical_device, &n, nullptr);
    std::vector<VkQueueFamilyProperties> families(n);
    vkGetPhysicalDeviceQueueFamilyProperties(user.physical_device, &n, families.data());
    if (user.queue_family >= n)
        fail("vulkan: vulkan_user_device::queue_family is ", user.queue_family, " but ",
             chosen_.properties.deviceName, " has ", n, " queue families");
    if (!(families[user.queue_family].queueFlags & VK_QUEUE_COMPUTE_BIT))
        fail("vulkan: queue family ", user.queue_family, " of ", chosen_.properties.deviceName,
             " does not support compute");
    owns_ = false;
    chosen_.graphics = (families[user.queue_family].queueFlags & VK_QUEUE_GRAPHICS_BIT) != 0;
    device_ = user.device;
    queue_ = user.queue;
    chosen_.queue_family = user.queue_family;
    vkGetPhysicalDeviceMemoryProperties(chosen_.handle, &memory_);
    read_limits();
}

VOXRAY_HOST_INLINE void context::read_limits() {
    auto m3 = vk_struct<VkPhysicalDeviceMaintenance3Properties>(
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES);
    auto props = vk_struct<VkPhysicalDeviceProperties2>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &m3);
#ifdef VK_VERSION_1_3
    // maxBufferSize exists only with maintenance4 (core in 1.3); chaining the struct
    // on a device without it would be invalid.
    auto m4 = vk_struct<VkPhysicalDeviceMaintenance4Properties>(
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_PROPERTIES);
    bool has_m4 = chosen_.properties.apiVersion >= VK_API_VERSION_1_3 ||
                  has_extension(device_extensions(chosen_.handle), "VK_KHR_maintenance4");
    if (has_m4) m3.pNext = &m4;
#endif
    vkGetPhysicalDeviceProperties2(chosen_.handle, &props);
    max_allocation_ = m3.maxMemoryAllocationSize;
    max_buffer_ = max_allocation_;
#ifdef VK_VERSION_1_3
    if (has_m4) max_buffer_ = m4.maxBufferSize;
#endif
}

VOXRAY_HOST_INLINE void context::create_device() {
    float priority = 1.0f;
    auto queue = vk_struct<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
    queue.queueFamilyIndex = chosen_.queue_family;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    // Buffer device addresses are the only feature the trace shaders need (addresses
    // travel as uvec2, so not even shaderInt64); the frame passes' 64-bit atomics are
    // enabled where the device has them.
    auto v12 = vk_struct<VkPhysicalDeviceVulkan12Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
    v12.bufferDeviceAddress = VK_TRUE;
    v12.shaderBufferInt64Atomics = chosen_.int64_atomics ? VK_TRUE : VK_FALSE;
    VkPhysicalDeviceFeatures core{};
    core.shaderInt64 = chosen_.int64_atomics ? VK_TRUE : VK_FALSE;
    core.multiDrawIndirect = chosen_.indirect_draws ? VK_TRUE : VK_FALSE;
    core.drawIndirectFirstInstance = chosen_.indirect_draws ? VK_TRUE : VK_FALSE;
    auto info = vk_struct<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &v12);
    info.pEnabledFeatures = &core;
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue;
    const char* portability = "VK_KHR_portability_subset";
    if (chosen_.portability_subset) {
        info.enabledExtensionCount = 1;
        info.ppEnabledExtensionNames = &portability;
    }
    vk_check(vkCreateDevice(chosen_.handle, &info, nullptr, &device_), "vkCreateDevice");
    vkGetDeviceQueue(device_, chosen_.queue_family, 0, &queue_);
}

VOXRAY_HOST_INLINE std::shared_ptr<context> shared_context(const vulkan_options& options) {
    if (options.user_device) return std::make_shared<context>(*options.user_device);
    static std::mutex lock;
    static std::weak_ptr<const instance> the_instance;
    static std::vector<std::weak_ptr<context>> contexts;
    std::lock_guard guard(lock);
    std::shared_ptr<const instance> inst = the_instance.lock();
    if (!inst) the_instance = inst = std::make_shared<const instance>();
    candidate chosen = choose_device(inst->handle(), options);
    std::erase_if(contexts, [](const std::weak_ptr<context>& c) { return c.expired(); });
    for (auto& weak : contexts)
        if (auto c = weak.lock(); c && c->physical_device() == chosen.handle) return c;
    auto made = std::make_shared<context>(inst, chosen);
    contexts.push_back(made);
    return made;
}

}  // namespace voxray::vulkan_detail
