// RAII owners for OpenCL objects. Each handle releases its object exactly once; copies
// are not allowed (use std::shared_ptr of the owner to share), moves transfer it. Keeping
// release in the destructor means every error path — check() throws — leaks nothing.
#pragma once
#include <CL/cl.h>

#include <utility>

namespace voxray::opencl_detail {

template <class Handle, cl_int (*Release)(Handle)>
class cl_handle {
public:
    cl_handle() = default;
    explicit cl_handle(Handle h) : h_(h) {}
    cl_handle(const cl_handle&) = delete;
    cl_handle& operator=(const cl_handle&) = delete;
    cl_handle(cl_handle&& o) noexcept : h_(std::exchange(o.h_, nullptr)) {}
    cl_handle& operator=(cl_handle&& o) noexcept {
        if (this != &o) {
            reset();
            h_ = std::exchange(o.h_, nullptr);
        }
        return *this;
    }
    ~cl_handle() { reset(); }

    // The release status is ignored: there is nothing useful to do with a failure to
    // free, and destructors must not throw.
    void reset() {
        if (h_) Release(h_);
        h_ = nullptr;
    }
    Handle get() const { return h_; }
    explicit operator bool() const { return h_ != nullptr; }

private:
    Handle h_ = nullptr;
};

using context_handle = cl_handle<cl_context, clReleaseContext>;
using queue_handle = cl_handle<cl_command_queue, clReleaseCommandQueue>;
using program_handle = cl_handle<cl_program, clReleaseProgram>;
using kernel_handle = cl_handle<cl_kernel, clReleaseKernel>;
using mem_handle = cl_handle<cl_mem, clReleaseMemObject>;
using event_handle = cl_handle<cl_event, clReleaseEvent>;

}  // namespace voxray::opencl_detail
