// The mesher kernel (meshing/kernel.h) on an OpenCL device: chunks in, the CPU mesher's
// quads and POP order out (meshing/kernel_mesher.hpp). The program is `mesher`, built
// once per device like the structures' programs; its passes run through the frame-pass
// runner (opencl/passes.hpp), the chunks are its blob and the meshes its frame.
//
//   voxray::opencl_chunk_mesher mesher({.ambient_occlusion = true});
//   std::vector<voxray::meshing::chunk_mesh> meshes = mesher.mesh(chunks);
#pragma once
#include <CL/cl.h>

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#if !defined(VOXRAY_LINKED_OPENCL)
#error "voxray/opencl/chunk_mesher.hpp needs voxray::opencl: link it"
#endif
#include "voxray/meshing/kernel_mesher.hpp"
#include "voxray/opencl/buffer.hpp"
#include "voxray/opencl/device.hpp"
#include "voxray/opencl/error.hpp"
#include "voxray/opencl/handles.hpp"
#include "voxray/opencl/passes.hpp"
#include "voxray/opencl/program_cache.hpp"

namespace voxray::opencl_detail {

class mesher_device {
public:
    static constexpr const char* backend = "opencl";

    explicit mesher_device(const opencl_options& options = {}) : ctx_(acquire_device_context(options)) {
        if (options.user_context) {
            check(clRetainCommandQueue(options.user_context->queue), "clRetainCommandQueue", "the application's queue");
            queue_ = queue_handle(options.user_context->queue);
        } else {
            cl_int status = CL_SUCCESS;
            queue_ = queue_handle(clCreateCommandQueue(ctx_->context(), ctx_->device(), 0, &status));
            check(status, "clCreateCommandQueue", "opening device '" + ctx_->device_name() + "'");
        }
    }

    std::string device_name() const { return ctx_->device_name(); }
    void upload(std::span<const std::uint32_t> words) {
        std::uint64_t bytes = words.size_bytes();
        check_alloc_limit("the mesher's chunks", bytes, ctx_->max_alloc_bytes(), ctx_->device_name());
        blob_.reserve(ctx_->context(), bytes);
        check(clEnqueueWriteBuffer(queue_.get(), blob_.get(), CL_TRUE, 0, static_cast<std::size_t>(bytes),
                                   words.data(), 0, nullptr, nullptr),
              "clEnqueueWriteBuffer", "uploading the mesher's chunks");
    }
    void frame_reserve(std::size_t words) { passes_.reserve(*ctx_, words); }
    void frame_write(std::size_t at, std::span<const std::uint32_t> words) { passes_.write(queue_.get(), at, words); }
    void frame_read(std::size_t at, std::span<std::uint32_t> words) { passes_.read(queue_.get(), at, words); }
    void run_pass(std::uint32_t pass, std::uint64_t items) {
        passes_.run(*ctx_, queue_.get(), ctx_->program(mesher_program), "vx_pass_mesher", blob_.get(), pass, items,
                    64);
    }

private:
    std::shared_ptr<device_context> ctx_;
    queue_handle queue_;
    device_buffer blob_{CL_MEM_READ_ONLY, "the mesher's chunks"};
    pass_runner passes_{false};
};

}  // namespace voxray::opencl_detail

namespace voxray {
using opencl_chunk_mesher = meshing::kernel_mesher<opencl_detail::mesher_device>;
}  // namespace voxray
