// Incremental updates on OpenCL: the dirty words of a structure blob travel to the device
// in one commit packet (sync/commit_layout.h) with one write, and the portable commit
// kernel (sync/commit.h, entry point vx_commit in kernels/commit.cl, a program of its own) scatters them into
// the device blob. Cost: one transfer of the changed words plus a small table, whatever
// the size of the world.
#pragma once
#include <CL/cl.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>

#include "voxray/opencl/buffer.hpp"
#include "voxray/opencl/program_cache.hpp"
#include "voxray/sync/commit_packet.hpp"

namespace voxray::opencl_detail {

class committer {
public:
    explicit committer(std::shared_ptr<device_context> ctx) : ctx_(std::move(ctx)) {}

    // Writes the words of `ranges` (normalized, non-empty) from `blob` into `device_blob`.
    // Returns the bytes sent. Blocking: the caller's blob may change right after.
    std::uint64_t commit(cl_command_queue queue, cl_mem device_blob, std::span<const std::uint32_t> blob,
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

private:
    void create_kernel() {
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

    std::shared_ptr<device_context> ctx_;
    kernel_handle kernel_;
    std::size_t local_size_ = 1;
    sync::commit_packer packer_;
    device_buffer packet_{CL_MEM_READ_ONLY, "the commit packet"};
};

}  // namespace voxray::opencl_detail
