// The frame passes' transfers and runs (declared in opencl/passes.hpp).
#pragma once
#include <CL/cl.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <string>

#include "voxray/opencl/passes.hpp"

namespace voxray::opencl_detail {

VOXRAY_HOST_INLINE void pass_runner::write(cl_command_queue queue, std::size_t at,
                                           std::span<const std::uint32_t> words) {
    check_range(at, words.size());
    if (words.empty()) return;
    check(clEnqueueWriteBuffer(queue, frame_.get(), CL_TRUE, at * 4, words.size_bytes(), words.data(), 0, nullptr,
                               nullptr),
          "clEnqueueWriteBuffer", "writing frame words");
}

VOXRAY_HOST_INLINE void pass_runner::read(cl_command_queue queue, std::size_t at, std::span<std::uint32_t> words) {
    check_range(at, words.size());
    if (words.empty()) return;
    check(clEnqueueReadBuffer(queue, frame_.get(), CL_TRUE, at * 4, words.size_bytes(), words.data(), 0, nullptr,
                              nullptr),
          "clEnqueueReadBuffer", "reading frame words");
}

VOXRAY_HOST_INLINE void pass_runner::run(const device_context& ctx, cl_command_queue queue, cl_program program,
                                         const std::string& entry, cl_mem blob, std::uint32_t pass, std::uint64_t count,
                                         std::size_t local_limit) {
    if (!frame_.get()) fail("OpenCL: a frame pass ran before the frame buffer was reserved");
    if (count == 0) return;
    if (count > std::numeric_limits<cl_uint>::max() - local_limit)
        fail("OpenCL: ", count, " items in one frame pass, more than its 32-bit count allows");
    if (!kernel_) {
        // The visibility buffer's nearest hit is a 64-bit atomic max (world/frame/passes.h).
        if (needs_int64_atomics_ &&
            device_string(ctx.device(), CL_DEVICE_EXTENSIONS).find("cl_khr_int64_extended_atomics") ==
                std::string::npos)
            fail("OpenCL: the frame passes need cl_khr_int64_extended_atomics, which ", ctx.device_name(),
                 " does not offer");
        kernel_ = create_kernel(program, entry);
    }
    cl_mem frame = frame_.get();
    cl_uint n = cl_uint(count);
    check(clSetKernelArg(kernel_.get(), 0, sizeof blob, &blob), "clSetKernelArg", "setting the blob");
    check(clSetKernelArg(kernel_.get(), 1, sizeof frame, &frame), "clSetKernelArg", "setting the frame");
    check(clSetKernelArg(kernel_.get(), 2, sizeof pass, &pass), "clSetKernelArg", "setting the pass");
    check(clSetKernelArg(kernel_.get(), 3, sizeof n, &n), "clSetKernelArg", "setting the count");
    std::size_t local = std::min(local_limit, group_size_for(kernel_.get(), ctx.device()));
    std::size_t global = (std::size_t(n) + local - 1) / local * local;
    check(clEnqueueNDRangeKernel(queue, kernel_.get(), 1, nullptr, &global, &local, 0, nullptr, nullptr),
          "clEnqueueNDRangeKernel", "running frame pass " + std::to_string(pass));
    check(clFinish(queue), "clFinish", "running frame pass " + std::to_string(pass));
}

}  // namespace voxray::opencl_detail
