// Choosing the OpenCL device. By default the first GPU of any platform, else the first
// device of any type (PoCL's CPU device on machines without a GPU). Options narrow the
// choice by case-insensitive substrings of the platform and device names, or name the
// application's own context, device and queue (opencl/interop.hpp).
#pragma once
#include <CL/cl.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "voxray/opencl/error.hpp"
#include "voxray/core/host_code.hpp"
#include "voxray/opencl/interop.hpp"

namespace voxray {

struct opencl_options {
    std::string platform;  // substring of the platform name; empty: any
    std::string device;    // substring of the device name; empty: any
    bool prefer_gpu = true;  // among the matches, take a GPU before other device types
    // Work-items per group of the trace kernels (a power of two, within the kernel's limit).
    // 0: the environment variable VOXRAY_GROUP_SIZE if set, else the largest multiple of
    // the device's preferred multiple up to 64.
    std::size_t group_size = 0;
    // Run in the application's context and queue instead of choosing a device (see
    // opencl/interop.hpp); the fields above are then ignored.
    std::optional<opencl_user_context> user_context;
};

namespace opencl_detail {

VOXRAY_HOST_INLINE std::string platform_string(cl_platform_id p, cl_platform_info what);

VOXRAY_HOST_INLINE std::string device_string(cl_device_id d, cl_device_info what);

template <class T>
T device_value(cl_device_id d, cl_device_info what) {
    T value{};
    check(clGetDeviceInfo(d, what, sizeof(T), &value, nullptr), "clGetDeviceInfo");
    return value;
}

inline bool contains_nocase(const std::string& text, const std::string& part) {
    auto lower = [](std::string s) {
        for (auto& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
        return s;
    };
    return lower(text).find(lower(part)) != std::string::npos;
}

struct device_choice {
    cl_platform_id platform = nullptr;
    cl_device_id device = nullptr;
    std::string platform_name, device_name;
};

// What was found, for error messages: "'PoCL': ['pthread-...'], 'Other': []".
VOXRAY_HOST_INLINE std::string describe(const std::vector<std::pair<std::string, std::vector<std::string>>>& found);

inline constexpr const char* zero_devices_hint =
    ". If PoCL is installed, note that it reports zero devices when its cache folder is not "
    "writable: set POCL_CACHE_DIR to a writable folder (by default it uses $HOME/.cache/pocl)";

VOXRAY_HOST_INLINE device_choice select_device(const opencl_options& options);

// The application's context, device and queue (opencl/interop.hpp), checked to fit together.
VOXRAY_HOST_INLINE device_choice check_user_context(const opencl_user_context& user);

}  // namespace opencl_detail
}  // namespace voxray

// The definitions: here, or compiled once in voxray::kernels (core/host_code.hpp).
#if VOXRAY_HOST_DEFINITIONS
#include "voxray/opencl/detail/device.hpp"
#endif
