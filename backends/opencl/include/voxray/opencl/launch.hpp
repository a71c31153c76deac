// Kernel objects and their work-group sizes, shared by the trace entries (engine.hpp) and
// the frame passes (passes.hpp).
#pragma once
#include <CL/cl.h>

#include <algorithm>
#include <cstddef>
#include <string>

#include "voxray/opencl/error.hpp"
#include "voxray/opencl/handles.hpp"

namespace voxray::opencl_detail {

// Work-items per group. 64 fills a wavefront (AMD) or two warps (NVIDIA) and is a
// multiple of every common SIMD width; the kernel may allow less (register pressure).
inline constexpr std::size_t preferred_group_size = 64;

inline kernel_handle create_kernel(cl_program program, const std::string& entry) {
    cl_int status = CL_SUCCESS;
    kernel_handle kernel(clCreateKernel(program, entry.c_str(), &status));
    check(status, "clCreateKernel", "looking up " + entry + " (backends/opencl/kernels/entry.cl)");
    return kernel;
}

// The largest multiple of the device's preferred multiple that is at most
// preferred_group_size and allowed for this kernel; at least 1.
inline std::size_t choose_group_size(std::size_t kernel_max, std::size_t multiple) {
    std::size_t limit = std::min(preferred_group_size, std::max<std::size_t>(kernel_max, 1));
    multiple = std::max<std::size_t>(multiple, 1);
    return multiple <= limit ? limit / multiple * multiple : limit;
}

// The most work-items a group of this kernel may have on this device.
inline std::size_t kernel_group_limit(cl_kernel kernel, cl_device_id device) {
    std::size_t kernel_max = 0;
    check(clGetKernelWorkGroupInfo(kernel, device, CL_KERNEL_WORK_GROUP_SIZE, sizeof kernel_max, &kernel_max, nullptr),
          "clGetKernelWorkGroupInfo");
    return kernel_max;
}

inline std::size_t group_size_for(cl_kernel kernel, cl_device_id device) {
    std::size_t kernel_max = kernel_group_limit(kernel, device), multiple = 1;
    check(clGetKernelWorkGroupInfo(kernel, device, CL_KERNEL_PREFERRED_WORK_GROUP_SIZE_MULTIPLE, sizeof multiple,
                                   &multiple, nullptr),
          "clGetKernelWorkGroupInfo");
    return choose_group_size(kernel_max, multiple);
}

}  // namespace voxray::opencl_detail
