// The Vulkan instance, the chosen physical device, its logical device and one compute
// queue. Everything else in the backend borrows these handles from one `context`, which
// either creates them or takes the application's (vulkan_options::user_device).
// Tracers share contexts (shared_context below): one VkInstance per process and one
// VkDevice per physical device, however many structures are traced, destroyed when the
// last tracer using them goes.
//
// Needs Vulkan 1.2 for buffer device addresses: the shaders reach structure, rays and
// hits through 64-bit addresses in push constants, so no descriptor and therefore no
// maxStorageBufferRange (128 MiB on lavapipe) limits a structure's size.
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#include "voxray/core/host_code.hpp"
#include "voxray/vulkan/check.hpp"
#include "voxray/vulkan/options.hpp"

namespace voxray::vulkan_detail {

inline constexpr std::uint32_t required_api = VK_API_VERSION_1_2;

inline bool has_extension(const std::vector<VkExtensionProperties>& list, const char* name) {
    return std::any_of(list.begin(), list.end(),
                       [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

VOXRAY_HOST_INLINE std::vector<VkExtensionProperties> device_extensions(VkPhysicalDevice pd);

// Lower is better: a real GPU first, a CPU implementation (lavapipe) last.
inline int type_rank(VkPhysicalDeviceType t) {
    switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
    }
}

// One physical device as seen during selection; `problem` is empty when it is usable.
struct candidate {
    VkPhysicalDevice handle = VK_NULL_HANDLE;
    VkPhysicalDeviceProperties properties{};
    std::uint32_t queue_family = 0;
    bool portability_subset = false;
    bool int64_atomics = false;  // shaderInt64 and shaderBufferInt64Atomics (the frame passes)
    bool graphics = false;       // the queue family draws too (the raster path, chunk_raster.hpp)
    bool indirect_draws = false; // multiDrawIndirect and drawIndirectFirstInstance (the same)
    std::string problem;
};

VOXRAY_HOST_INLINE candidate inspect(VkPhysicalDevice pd);

// The process's VkInstance, shared by every context voxray creates.
class instance {
public:
    instance() { create(); }
    ~instance() { vkDestroyInstance(handle_, nullptr); }
    instance(const instance&) = delete;
    instance& operator=(const instance&) = delete;
    VkInstance handle() const { return handle_; }

private:
    void create();

    VkInstance handle_ = VK_NULL_HANDLE;
};

// The physical device the options ask for (vulkan_options::device, else the environment
// variable VOXRAY_VULKAN_DEVICE), else the best usable one: a GPU before a CPU device.
VOXRAY_HOST_INLINE candidate choose_device(VkInstance inst, const vulkan_options& options);

class context {
public:
    // A device of its own on `chosen`, a physical device of `inst` (shared_context()
    // shares them).
    context(std::shared_ptr<const instance> inst, const candidate& chosen);
    // The application's device (vulkan_options::user_device).
    explicit context(const vulkan_user_device& user) { borrow(user); }
    ~context() { destroy(); }
    context(const context&) = delete;
    context& operator=(const context&) = delete;

    VkDevice device() const { return device_; }
    VkPhysicalDevice physical_device() const { return chosen_.handle; }
    VkQueue queue() const { return queue_; }
    std::uint32_t queue_family() const { return chosen_.queue_family; }
    const VkPhysicalDeviceProperties& properties() const { return chosen_.properties; }
    const VkPhysicalDeviceMemoryProperties& memory() const { return memory_; }
    std::string name() const { return chosen_.properties.deviceName; }
    // Largest single allocation and buffer the device allows (maintenance3 / maintenance4).
    VkDeviceSize max_allocation() const { return max_allocation_; }
    VkDeviceSize max_buffer() const { return max_buffer_; }

    // False on the application's device (vulkan_options::user_device): nothing to destroy.
    bool owns_device() const { return owns_; }
    // Whether 64-bit buffer atomics are enabled (the frame passes' visibility buffer):
    // on a device voxray creates, wherever the device has them; never assumed of the
    // application's device, whose enabled features voxray cannot see.
    bool int64_atomics() const { return owns_ && chosen_.int64_atomics; }
    // Whether the queue draws (the raster path of chunk meshes, voxray/vulkan/chunk_raster.hpp).
    bool graphics() const { return chosen_.graphics; }
    // Whether one vkCmdDrawIndirect may issue many draws whose first instance is not 0;
    // like int64_atomics, never assumed of the application's device.
    bool indirect_draws() const { return owns_ && chosen_.indirect_draws; }
    // Held around every vkQueueSubmit: the tracers sharing this context share its queue,
    // which Vulkan requires to be externally synchronized.
    std::mutex& queue_lock() const { return queue_lock_; }

private:
    // The application's handles: checked, then used as they are, never destroyed.
    void borrow(const vulkan_user_device& user);

    void read_limits();

    void create_device();

    void destroy() {
        if (!owns_) return;
        if (device_) vkDestroyDevice(device_, nullptr);
        device_ = VK_NULL_HANDLE;
    }

    std::shared_ptr<const instance> instance_;  // null on the application's device
    mutable std::mutex queue_lock_;
    VkDevice device_ = VK_NULL_HANDLE;
    VkQueue queue_ = VK_NULL_HANDLE;
    bool owns_ = true;
    candidate chosen_;
    VkPhysicalDeviceMemoryProperties memory_{};
    VkDeviceSize max_allocation_ = 0;
    VkDeviceSize max_buffer_ = 0;
};

// The context a tracer with these options uses: the application's device as given, or
// else the one voxray context of the physical device the options choose, created on
// first use with the process's one instance. Both go when their last user does.
VOXRAY_HOST_INLINE std::shared_ptr<context> shared_context(const vulkan_options& options);

}  // namespace voxray::vulkan_detail

// The definitions: here, or compiled once in voxray::kernels (core/host_code.hpp).
#if VOXRAY_HOST_DEFINITIONS
#include "voxray/vulkan/detail/device.hpp"
#endif
