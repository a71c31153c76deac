// Every Vulkan call the backend makes goes through vk_check, so a failure surfaces as a
// voxray::error naming the call and its VkResult rather than as a crash later on.
#pragma once
#include <cstdint>
#include <string>

#include <vulkan/vulkan.h>

#include "voxray/core/error.hpp"
#include "voxray/core/host_code.hpp"

namespace voxray::vulkan_detail {

VOXRAY_HOST_INLINE const char* result_name(VkResult r);

// Throws voxray::error("vulkan: vkCall failed: VK_ERROR_... (code)") unless r is VK_SUCCESS.
inline void vk_check(VkResult r, const char* call) {
    if (r != VK_SUCCESS) fail("vulkan: ", call, " failed: ", result_name(r), " (", int(r), ")");
}

// A zeroed Vulkan struct with its sType (and pNext) set: `T x{sType}` would leave the
// other members value-initialized too, but -Wextra warns about it in users' builds.
template <class T>
T vk_struct(VkStructureType type, void* next = nullptr) {
    T s{};
    s.sType = type;
    s.pNext = next;
    return s;
}

// Packed Vulkan version as "major.minor.patch".
VOXRAY_HOST_INLINE std::string version_string(std::uint32_t v);

}  // namespace voxray::vulkan_detail

// The definitions: here, or compiled once in voxray::kernels (core/host_code.hpp).
#if VOXRAY_HOST_DEFINITIONS
#include "voxray/vulkan/detail/check.hpp"
#endif
