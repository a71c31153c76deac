// Frame passes on OpenCL, for structures registered with PASSES (the chunked world's
// world/frame/passes.h): the vx_pass_<name> kernel of the structure's program, a frame
// buffer of words that the passes read and write, host access to those words, and one
// pass run to completion. It owns no device: the engine (opencl/engine.hpp) lends it its
// context, queue, program and blob on every call, as the Vulkan one (vulkan/passes.hpp).
#pragma once
#include <CL/cl.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <string>

#include "voxray/opencl/buffer.hpp"
#include "voxray/core/host_code.hpp"
#include "voxray/opencl/device.hpp"
#include "voxray/opencl/error.hpp"
#include "voxray/opencl/launch.hpp"
#include "voxray/opencl/program_cache.hpp"

namespace voxray::opencl_detail {

class pass_runner {
public:
    // The world's frame passes keep the nearest hit by a 64-bit atomic max; other pass
    // programs (the mesher kernel) need no 64-bit atomics.
    explicit pass_runner(bool needs_int64_atomics = true) : needs_int64_atomics_(needs_int64_atomics) {}

    // Room for `words` frame words (grow-only; growing drops the old contents).
    void reserve(const device_context& ctx, std::size_t words) {
        std::uint64_t bytes = std::max<std::uint64_t>(std::uint64_t(words) * 4, 8);
        check_alloc_limit("the frame buffer", bytes, ctx.max_alloc_bytes(), ctx.device_name());
        frame_.reserve(ctx.context(), bytes);
    }

    void write(cl_command_queue queue, std::size_t at, std::span<const std::uint32_t> words);

    void read(cl_command_queue queue, std::size_t at, std::span<std::uint32_t> words);

    // Runs `count` items of pass `pass` (kernel `entry` of `program`) over `blob`, in
    // groups of at most `local_limit` items, and waits for them.
    void run(const device_context& ctx, cl_command_queue queue, cl_program program, const std::string& entry,
             cl_mem blob, std::uint32_t pass, std::uint64_t count, std::size_t local_limit);

    // Bytes of device memory the frame buffer holds.
    std::uint64_t bytes() const { return frame_.capacity(); }

private:
    void check_range(std::size_t at, std::size_t n) const {
        if ((at + n) * 4 > frame_.capacity())
            fail("OpenCL: frame words [", at, ", ", at + n, ") outside the frame buffer's ", frame_.capacity() / 4,
                 " words");
    }

    bool needs_int64_atomics_;
    kernel_handle kernel_;  // vx_pass_<name>, looked up on the first pass
    device_buffer frame_{CL_MEM_READ_WRITE, "the frame buffer"};
};

}  // namespace voxray::opencl_detail

// The definitions: here, or compiled once in voxray::kernels (core/host_code.hpp).
#if VOXRAY_HOST_DEFINITIONS
#include "voxray/opencl/detail/passes.hpp"
#endif
