// Platform and device selection (declared in opencl/device.hpp).
#pragma once
#include <CL/cl.h>

#include <algorithm>
#include <cctype>
#include <string>
#include <vector>

#include "voxray/opencl/device.hpp"

namespace voxray::opencl_detail {

VOXRAY_HOST_INLINE std::string platform_string(cl_platform_id p, cl_platform_info what) {
    std::size_t size = 0;
    check(clGetPlatformInfo(p, what, 0, nullptr, &size), "clGetPlatformInfo");
    std::string s(size, '\0');
    check(clGetPlatformInfo(p, what, size, s.data(), nullptr), "clGetPlatformInfo");
    while (!s.empty() && s.back() == '\0') s.pop_back();
    return s;
}

VOXRAY_HOST_INLINE std::string device_string(cl_device_id d, cl_device_info what) {
    std::size_t size = 0;
    check(clGetDeviceInfo(d, what, 0, nullptr, &size), "clGetDeviceInfo");
    std::string s(size, '\0');
    check(clGetDeviceInfo(d, what, size, s.data(), nullptr), "clGetDeviceInfo");
    while (!s.empty() && s.back() == '\0') s.pop_back();
    return s;
}

VOXRAY_HOST_INLINE std::string describe(const std::vector<std::pair<std::string, std::vector<std::string>>>& found) {
    std::string s;
    for (auto& [platform, devices] : found) {
        if (!s.empty()) s += ", ";
        s += "'" + platform + "': [";
        for (std::size_t i = 0; i < devices.size(); ++i) s += (i ? ", '" : "'") + devices[i] + "'";
        s += "]";
    }
    return s.empty() ? "nothing" : s;
}

VOXRAY_HOST_INLINE device_choice select_device(const opencl_options& options) {
    cl_uint platform_count = 0;
    cl_int status = clGetPlatformIDs(0, nullptr, &platform_count);
    if (status == -1001 /* CL_PLATFORM_NOT_FOUND_KHR: an ICD loader without drivers */) platform_count = 0;
    else check(status, "clGetPlatformIDs");
    if (platform_count == 0)
        throw opencl_error(std::string("OpenCL: found 0 platforms (is an OpenCL driver installed? Debian: "
                                       "pocl-opencl-icd)") + zero_devices_hint, CL_DEVICE_NOT_FOUND);
    std::vector<cl_platform_id> platforms(platform_count);
    check(clGetPlatformIDs(platform_count, platforms.data(), nullptr), "clGetPlatformIDs");

    std::vector<std::pair<std::string, std::vector<std::string>>> found;
    device_choice first_any, first_gpu;
    for (cl_platform_id p : platforms) {
        std::string pname = platform_string(p, CL_PLATFORM_NAME);
        found.push_back({pname, {}});
        cl_uint count = 0;
        status = clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, 0, nullptr, &count);
        if (status == CL_DEVICE_NOT_FOUND) continue;  // a platform with no devices is not an error
        check(status, "clGetDeviceIDs");
        std::vector<cl_device_id> devices(count);
        check(clGetDeviceIDs(p, CL_DEVICE_TYPE_ALL, count, devices.data(), nullptr), "clGetDeviceIDs");
        for (cl_device_id d : devices) {
            std::string dname = device_string(d, CL_DEVICE_NAME);
            found.back().second.push_back(dname);
            if (!device_value<cl_bool>(d, CL_DEVICE_AVAILABLE)) continue;
            if (!options.platform.empty() && !contains_nocase(pname, options.platform)) continue;
            if (!options.device.empty() && !contains_nocase(dname, options.device)) continue;
            device_choice c{p, d, pname, dname};
            if (!first_any.device) first_any = c;
            if (!first_gpu.device && (device_value<cl_device_type>(d, CL_DEVICE_TYPE) & CL_DEVICE_TYPE_GPU))
                first_gpu = c;
        }
    }
    if (options.prefer_gpu && first_gpu.device) return first_gpu;
    if (first_any.device) return first_any;

    std::string wanted;
    if (!options.platform.empty()) wanted += " platform matching '" + options.platform + "'";
    if (!options.device.empty()) wanted += " device matching '" + options.device + "'";
    bool none_at_all = std::all_of(found.begin(), found.end(), [](auto& f) { return f.second.empty(); });
    throw opencl_error("OpenCL: no available" + (wanted.empty() ? std::string(" device") : wanted) +
                           "; found " + std::to_string(platform_count) + " platform(s), with their devices: " +
                           describe(found) + (none_at_all ? zero_devices_hint : ""),
                       CL_DEVICE_NOT_FOUND);
}

VOXRAY_HOST_INLINE device_choice check_user_context(const opencl_user_context& user) {
    auto missing = [](const char* field) {
        fail("OpenCL: opencl_user_context::", field, " is null; voxray needs all of context, device and queue");
    };
    if (!user.context) missing("context");
    if (!user.device) missing("device");
    if (!user.queue) missing("queue");
    device_choice c{device_value<cl_platform_id>(user.device, CL_DEVICE_PLATFORM), user.device, {}, {}};
    c.platform_name = platform_string(c.platform, CL_PLATFORM_NAME);
    c.device_name = device_string(user.device, CL_DEVICE_NAME);

    cl_uint count = 0;
    check(clGetContextInfo(user.context, CL_CONTEXT_NUM_DEVICES, sizeof count, &count, nullptr), "clGetContextInfo",
          "inspecting the application's context");
    std::vector<cl_device_id> devices(count);
    check(clGetContextInfo(user.context, CL_CONTEXT_DEVICES, count * sizeof(cl_device_id), devices.data(), nullptr),
          "clGetContextInfo", "inspecting the application's context");
    if (std::find(devices.begin(), devices.end(), user.device) == devices.end())
        fail("OpenCL: device '", c.device_name, "' is not one of the ", count,
             " device(s) of the application's context");

    cl_context queue_context = nullptr;
    cl_device_id queue_device = nullptr;
    cl_command_queue_properties props = 0;
    check(clGetCommandQueueInfo(user.queue, CL_QUEUE_CONTEXT, sizeof queue_context, &queue_context, nullptr),
          "clGetCommandQueueInfo", "inspecting the application's queue");
    check(clGetCommandQueueInfo(user.queue, CL_QUEUE_DEVICE, sizeof queue_device, &queue_device, nullptr),
          "clGetCommandQueueInfo", "inspecting the application's queue");
    check(clGetCommandQueueInfo(user.queue, CL_QUEUE_PROPERTIES, sizeof props, &props, nullptr),
          "clGetCommandQueueInfo", "inspecting the application's queue");
    if (queue_context != user.context) fail("OpenCL: the application's queue belongs to another context");
    if (queue_device != user.device)
        fail("OpenCL: the application's queue is for another device than '", c.device_name, "'");
    if (props & CL_QUEUE_OUT_OF_ORDER_EXEC_MODE_ENABLE)
        fail("OpenCL: the application's queue is out of order (CL_QUEUE_OUT_OF_ORDER_EXEC_MODE_ENABLE); voxray needs "
             "an in-order queue");
    return c;
}

}  // namespace voxray::opencl_detail
