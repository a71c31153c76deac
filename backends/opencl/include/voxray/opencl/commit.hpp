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
#include "voxray/core/host_code.hpp"
#include "voxray/opencl/program_cache.hpp"
#include "voxray/sync/commit_packet.hpp"

namespace voxray::opencl_detail {

class committer {
public:
    explicit committer(std::shared_ptr<device_context> ctx) : ctx_(std::move(ctx)) {}

    // Writes the words of `ranges` (normalized, non-empty) from `blob` into `device_blob`.
    // Returns the bytes sent. Blocking: the caller's blob may change right after.
    std::uint64_t commit(cl_command_queue queue, cl_mem device_blob, std::span<const std::uint32_t> blob,
                         std::span<const word_range> ranges);

private:
    void create_kernel();

    std::shared_ptr<device_context> ctx_;
    kernel_handle kernel_;
    std::size_t local_size_ = 1;
    sync::commit_packer packer_;
    device_buffer packet_{CL_MEM_READ_ONLY, "the commit packet"};
};

}  // namespace voxray::opencl_detail

// The definitions: here, or compiled once in voxray::kernels (core/host_code.hpp).
#if VOXRAY_HOST_DEFINITIONS
#include "voxray/opencl/detail/commit.hpp"
#endif
