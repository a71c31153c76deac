// The compositing walk (appearance/walk.inc) on an OpenCL device, for any structure kernel:
// program <structure>_appearance (voxray_add_appearance_walk), built once per device like
// the structures' programs. The structure and its appearance table are uploaded once;
// each walk sends rays and reads pixels. Same arguments and results as the CPU walker
// (cpu/appearance_walk.hpp): the pixels agree bit for bit (tests/appearance).
//
//   voxray::opencl_appearance_walker<voxray::kernels::dense_grid_kernel> walker(blob, table);
//   std::vector<voxray::appearance_pixel> out = walker.walk(rays, light);
#pragma once
#include <CL/cl.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#if !defined(VOXRAY_LINKED_OPENCL)
#error "voxray/opencl/appearance_walk.hpp needs voxray::opencl: link it"
#endif
#include "voxray/appearance/walk_inputs.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/opencl/buffer.hpp"
#include "voxray/opencl/device.hpp"
#include "voxray/opencl/error.hpp"
#include "voxray/opencl/handles.hpp"
#include "voxray/opencl/launch.hpp"
#include "voxray/opencl/program_cache.hpp"

namespace voxray::opencl_detail {

// Program <name>_appearance: the walk over structure kernel `name`.
constexpr bool is_walk_program_of(const program_source& p, std::string_view name) {
    constexpr std::string_view suffix = "_appearance";
    return p.name.size() == name.size() + suffix.size() && p.name.starts_with(name) && p.name.ends_with(suffix);
}
// Whether structure kernel `name` has a walk program (voxray_add_appearance_walk: every
// structure, not the staged scene kernels), and which.
constexpr bool has_walk_program(std::string_view name) {
    for (const program_source& p : appearance_programs)
        if (is_walk_program_of(p, name)) return true;
    return false;
}
constexpr program_source find_walk_program(std::string_view name) {
    for (const program_source& p : appearance_programs)
        if (is_walk_program_of(p, name)) return p;
    return {name, nullptr};
}

}  // namespace voxray::opencl_detail

namespace voxray {

template <class Kernel>
class opencl_appearance_walker {
    static_assert(opencl_detail::has_walk_program(Kernel::name),
                  "this structure has no OpenCL walk program (voxray_add_appearance_walk, CMake)");

public:
    static constexpr const char* backend = "opencl";

    // `blob` is the structure's words, `table` the appearance of its voxels; both are
    // uploaded here and may die after the call.
    opencl_appearance_walker(std::span<const std::uint32_t> blob, const appearance::appearance_table& table,
                             const opencl_options& options = {})
        : ctx_(opencl_detail::acquire_device_context(options)) {
        namespace cl = opencl_detail;
        if (options.user_context) {
            cl::check(clRetainCommandQueue(options.user_context->queue), "clRetainCommandQueue",
                      "the application's queue");
            queue_ = cl::queue_handle(options.user_context->queue);
        } else {
            cl_int status = CL_SUCCESS;
            queue_ = cl::queue_handle(clCreateCommandQueue(ctx_->context(), ctx_->device(), 0, &status));
            cl::check(status, "clCreateCommandQueue", "opening device '" + ctx_->device_name() + "'");
        }
        kernel_ = cl::create_kernel(ctx_->program(cl::find_walk_program(Kernel::name)), "vx_appearance_walk");
        local_size_ = cl::group_size_for(kernel_.get(), ctx_->device());
        appearance::walk_words words(table);
        kind_ = words.kind, shadows_ = words.shadows;
        upload(blob_, blob, "the structure blob");
        upload(index_, words.index, "the ordinal index");
        upload(records_, words.records, "the appearance records");
        upload(faces_, words.faces, "the appearance face pool");
    }

    std::string device_name() const { return ctx_->device_name(); }

    // Rays' directions must be unit vectors (records are evaluated for them).
    std::vector<appearance_pixel> walk(std::span<const ray> rays, const appearance_light& light) {
        using opencl_detail::check;
        const std::uint32_t shadows_at = shadows_.at_for(light);
        std::vector<appearance_pixel> out(rays.size());
        if (rays.empty()) return out;
        if (rays.size() > 0xFFFFFFFFu) fail("OpenCL appearance walk: ", rays.size(), " rays, above 2^32 - 1");
        upload(rays_, std::span(reinterpret_cast<const std::uint32_t*>(rays.data()), rays.size() * 8), "the rays");
        std::uint64_t pixel_bytes = std::uint64_t(rays.size()) * sizeof(appearance_pixel);
        opencl_detail::check_alloc_limit("the walk's pixels", pixel_bytes, ctx_->max_alloc_bytes(),
                                         ctx_->device_name());
        pixels_.reserve(ctx_->context(), pixel_bytes);
        auto count = std::uint32_t(rays.size());
        cl_mem buffers[] = {blob_.get(), index_.get(), records_.get(), faces_.get(), rays_.get(), pixels_.get()};
        cl_uint arg = 0;
        for (cl_mem& b : buffers) set(arg++, b);
        for (std::uint32_t v : {count, kind_}) set(arg++, v);
        for (float v : {light.to_light.x, light.to_light.y, light.to_light.z, light.ambient, light.cutoff}) set(arg++, v);
        set(arg++, light.max_visits);
        set(arg++, shadows_at);
        std::size_t global = (std::size_t(count) + local_size_ - 1) / local_size_ * local_size_;
        check(clEnqueueNDRangeKernel(queue_.get(), kernel_.get(), 1, nullptr, &global, &local_size_, 0, nullptr,
                                     nullptr),
              "clEnqueueNDRangeKernel", "walking " + std::to_string(count) + " rays");
        check(clEnqueueReadBuffer(queue_.get(), pixels_.get(), CL_TRUE, 0, static_cast<std::size_t>(pixel_bytes),
                                  out.data(), 0, nullptr, nullptr),
              "clEnqueueReadBuffer", "reading the walk's pixels");
        appearance::check_walked(out);
        return out;
    }

private:
    template <class T>
    void set(cl_uint arg, const T& value) {
        opencl_detail::check(clSetKernelArg(kernel_.get(), arg, sizeof value, &value), "clSetKernelArg",
                             "argument " + std::to_string(arg) + " of vx_appearance_walk");
    }

    // Copies `words` (blocking: the caller's span may die right after).
    void upload(opencl_detail::device_buffer& to, std::span<const std::uint32_t> words, const char* what) {
        std::uint64_t bytes = std::max<std::uint64_t>(words.size_bytes(), 4);
        opencl_detail::check_alloc_limit(what, bytes, ctx_->max_alloc_bytes(), ctx_->device_name());
        to.reserve(ctx_->context(), bytes);
        if (words.empty()) return;
        opencl_detail::check(clEnqueueWriteBuffer(queue_.get(), to.get(), CL_TRUE, 0, words.size_bytes(),
                                                  words.data(), 0, nullptr, nullptr),
                             "clEnqueueWriteBuffer", std::string("uploading ") + what);
    }

    std::shared_ptr<opencl_detail::device_context> ctx_;
    opencl_detail::queue_handle queue_;
    opencl_detail::kernel_handle kernel_;
    std::size_t local_size_ = 1;
    std::uint32_t kind_ = 0;
    appearance::walk_shadows shadows_;
    opencl_detail::device_buffer blob_{CL_MEM_READ_ONLY, "the structure blob"};
    opencl_detail::device_buffer index_{CL_MEM_READ_ONLY, "the ordinal index"};
    opencl_detail::device_buffer records_{CL_MEM_READ_ONLY, "the appearance records"};
    opencl_detail::device_buffer faces_{CL_MEM_READ_ONLY, "the appearance face pool"};
    opencl_detail::device_buffer rays_{CL_MEM_READ_ONLY, "the rays"};
    opencl_detail::device_buffer pixels_{CL_MEM_WRITE_ONLY, "the walk's pixels"};
};

}  // namespace voxray
