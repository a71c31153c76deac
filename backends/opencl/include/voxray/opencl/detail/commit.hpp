// The commit packet's upload and scatter (declared in opencl/commit.hpp).
#pragma once
#include <CL/cl.h>

#include <cstdint>
#include <span>
#include <string>

#include "voxray/opencl/commit.hpp"

namespace voxray::opencl_detail {

VOXRAY_HOST_INLINE std::uint64_t committer::commit(cl_command_queue queue, cl_mem device_blob,
                                                   std::span<const std::uint32_t> blob,
                                                   std::span<const word_range> ranges) {
    if (!kernel_) create_kernel();
    std::span<const std::uint32_t> packet = packer_.pack(blob, ranges);
    std::uint64_t bytes = packet.size_bytes();
    check_alloc_limit("the commit packet", bytes, ctx_->max_alloc_bytes(), ctx_->device_name());
    packet_.reserve(ctx_->context(), bytes);
    check(clEnqueueWriteBuffer(queue, packet_.get(), CL_TRUE, 0, static_cast<std::size_t>(bytes), packet.data(),
                               0, nullptr, nullptr),
          "clEnqueueWriteBuffer", "sending a commit packet");
    cl_mem source = packet_.get();
    check(clSetKernelArg(kernel_.get(), 0, sizeof device_blob, &device_blob), "clSetKernelArg", "setting the blob");
    check(clSetKernelArg(kernel_.get(), 1, sizeof source, &source), "clSetKernelArg", "setting the packet");
    std::size_t words = packet[VX_COMMIT_HEADER_DATA_WORDS];
    std::size_t global = (words + local_size_ - 1) / local_size_ * local_size_;
    check(clEnqueueNDRangeKernel(queue, kernel_.get(), 1, nullptr, &global, &local_size_, 0, nullptr, nullptr),
          "clEnqueueNDRangeKernel", "committing " + std::to_string(words) + " words");
    // The queue is in order, so later traces see the new words; finishing here keeps
    // update() synchronous like upload(), and the timing honest.
    check(clFinish(queue), "clFinish", "committing an update");
    return bytes;
}

VOXRAY_HOST_INLINE void committer::create_kernel() {
    cl_int status = CL_SUCCESS;
    kernel_ = kernel_handle(clCreateKernel(ctx_->program(commit_program), "vx_commit", &status));
    check(status, "clCreateKernel", "looking up vx_commit (backends/opencl/kernels/commit.cl)");
    std::size_t kernel_max = 0;
    check(clGetKernelWorkGroupInfo(kernel_.get(), ctx_->device(), CL_KERNEL_WORK_GROUP_SIZE, sizeof kernel_max,
                                   &kernel_max, nullptr),
          "clGetKernelWorkGroupInfo");
    // 64 items a group, like the trace kernels, where the device allows it.
    local_size_ = kernel_max >= 64 ? 64 : (kernel_max > 0 ? kernel_max : 1);
}

}  // namespace voxray::opencl_detail
