// The device context's set-up and program builds (declared in opencl/program_cache.hpp).
#pragma once
#include <CL/cl.h>

#include <chrono>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include "voxray/opencl/program_cache.hpp"

namespace voxray::opencl_detail {

VOXRAY_HOST_INLINE device_context::device_context(const device_choice& choice) : choice_(choice) {
    cl_int status = CL_SUCCESS;
    cl_context_properties props[] = {CL_CONTEXT_PLATFORM,
                                     reinterpret_cast<cl_context_properties>(choice.platform), 0};
    context_ = context_handle(clCreateContext(props, 1, &choice_.device, nullptr, nullptr, &status));
    check(status, "clCreateContext", "opening device '" + choice_.device_name + "'");
    read_device();
}

VOXRAY_HOST_INLINE device_context::device_context(const device_choice& choice, cl_context borrowed) : choice_(choice) {
    check(clRetainContext(borrowed), "clRetainContext", "the application's context");
    context_ = context_handle(borrowed);
    read_device();
}

VOXRAY_HOST_INLINE void device_context::read_device() {
    max_alloc_ = device_value<cl_ulong>(choice_.device, CL_DEVICE_MAX_MEM_ALLOC_SIZE);
    max_group_ = device_value<std::size_t>(choice_.device, CL_DEVICE_MAX_WORK_GROUP_SIZE);
    auto fp = device_value<cl_device_fp_config>(choice_.device, CL_DEVICE_SINGLE_FP_CONFIG);
    correctly_rounded_ = (fp & CL_FP_CORRECTLY_ROUNDED_DIVIDE_SQRT) != 0;
    // -cl-std: the kernels are OpenCL C 1.2 (PoCL offers nothing newer anyway).
    // Correctly rounded division: only where the device offers it (the option is
    // invalid elsewhere); it makes the DDA's 1/d match the CPU backends bit for bit.
    options_ = "-cl-std=CL1.2";
    if (correctly_rounded_) options_ += " -cl-fp32-correctly-rounded-divide-sqrt";
}

VOXRAY_HOST_INLINE device_context::built_program device_context::build(const program_source& p) const {
    auto start = std::chrono::steady_clock::now();
    const char* source = p.source;
    cl_int status = CL_SUCCESS;
    program_handle program(clCreateProgramWithSource(context_.get(), 1, &source, nullptr, &status));
    check(status, "clCreateProgramWithSource", "the " + std::string(p.name) + " program");
    status = clBuildProgram(program.get(), 1, &choice_.device, options_.c_str(), nullptr, nullptr);
    if (status != CL_SUCCESS) {
        std::string log = build_log(program.get());
        if (log.size() > max_build_log_chars) log = log.substr(0, max_build_log_chars) + "\n[... log truncated]";
        throw opencl_error(std::string("OpenCL: clBuildProgram failed: ") + cl_status_name(status) + " (" +
                               std::to_string(status) + ") building the voxray " + std::string(p.name) +
                               " program for '" + choice_.device_name + "' with options '" + options_ +
                               "'. Build log:\n" + log,
                           status);
    }
    return {std::move(program), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

VOXRAY_HOST_INLINE std::string device_context::build_log(cl_program program) const {
    std::size_t size = 0;
    if (clGetProgramBuildInfo(program, choice_.device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size) != CL_SUCCESS)
        return "(no build log available)";
    std::string log(size, '\0');
    clGetProgramBuildInfo(program, choice_.device, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr);
    while (!log.empty() && log.back() == '\0') log.pop_back();
    return log;
}

VOXRAY_HOST_INLINE std::shared_ptr<device_context> acquire_device_context(const opencl_options& options) {
    static std::mutex mutex;
    if (options.user_context) {
        static std::map<std::pair<cl_context, cl_device_id>, std::weak_ptr<device_context>> borrowed;
        device_choice choice = check_user_context(*options.user_context);
        std::lock_guard lock(mutex);
        auto& slot = borrowed[{options.user_context->context, choice.device}];
        if (auto existing = slot.lock()) return existing;
        auto fresh = std::make_shared<device_context>(choice, options.user_context->context);
        slot = fresh;
        return fresh;
    }
    static std::map<cl_device_id, std::weak_ptr<device_context>> registry;
    device_choice choice = select_device(options);
    std::lock_guard lock(mutex);
    auto& slot = registry[choice.device];
    if (auto existing = slot.lock()) return existing;
    auto fresh = std::make_shared<device_context>(choice);
    slot = fresh;
    return fresh;
}

}  // namespace voxray::opencl_detail
