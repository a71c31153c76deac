// The work-group size of the GPU backends' trace kernels, when the application asks for
// one (vulkan_options::group_size, opencl_options::group_size) or the environment does
// (VOXRAY_GROUP_SIZE: to tune a device without rebuilding, scripts/device_bench.sh). Each
// backend checks the size against its device's limits and names both numbers when they
// clash.
#pragma once
#include <bit>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "voxray/core/error.hpp"

namespace voxray {

// Largest size asked for: every Vulkan device allows at least 128 invocations a group and
// every OpenCL device reports its own limit; 1024 is the most any common GPU allows.
inline constexpr std::uint32_t max_requested_group_size = 1024;

// `requested` if non-zero, else VOXRAY_GROUP_SIZE if set, else 0 (the backend's default).
// A size must be a power of two from 1 to 1024.
inline std::uint32_t requested_group_size(std::uint64_t requested) {
    std::string source = "group_size";
    std::uint64_t size = requested;
    if (size == 0) {
        const char* env = std::getenv("VOXRAY_GROUP_SIZE");
        if (!env || !*env) return 0;
        source = "VOXRAY_GROUP_SIZE";
        char* end = nullptr;
        size = std::strtoull(env, &end, 10);
        if (*end != '\0' || env[0] == '-') fail("VOXRAY_GROUP_SIZE is '", env, "', not a whole number");
    }
    if (size == 0 || size > max_requested_group_size || !std::has_single_bit(size))
        fail(source, " is ", size, ": a work-group size must be a power of two from 1 to ", max_requested_group_size);
    return std::uint32_t(size);
}

}  // namespace voxray
