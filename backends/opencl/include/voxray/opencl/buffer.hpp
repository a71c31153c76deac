// Device buffers that grow on demand, and the allocation limit every buffer is checked
// against. OpenCL caps a single allocation at CL_DEVICE_MAX_MEM_ALLOC_SIZE (often a
// quarter of device memory; 1-2 GiB on PoCL); going past it fails late and vaguely
// (CL_INVALID_BUFFER_SIZE or CL_MEM_OBJECT_ALLOCATION_FAILURE), so we check first and
// say which numbers disagree.
#pragma once
#include <CL/cl.h>

#include <cstdint>
#include <string>

#include "voxray/opencl/error.hpp"
#include "voxray/opencl/handles.hpp"

namespace voxray::opencl_detail {

// Throws when `bytes` of `what` cannot be one allocation on a device whose limit is
// `max_alloc_bytes`. A free function so that tests can feed it numbers no device has.
inline void check_alloc_limit(const char* what, std::uint64_t bytes, std::uint64_t max_alloc_bytes,
                              const std::string& device_name) {
    if (bytes > max_alloc_bytes)
        fail("OpenCL: ", what, " needs ", bytes, " bytes in one buffer, above the device's "
             "CL_DEVICE_MAX_MEM_ALLOC_SIZE of ", max_alloc_bytes, " bytes on '", device_name, "'");
}

// A buffer that is reallocated only when a request exceeds its capacity: traces of the
// same size (a render loop) then allocate nothing.
class device_buffer {
public:
    device_buffer(cl_mem_flags flags, const char* what) : flags_(flags), what_(what) {}

    // Makes room for `bytes` (> 0), keeping the old buffer when it is big enough.
    void reserve(cl_context context, std::uint64_t bytes) {
        if (mem_ && bytes <= capacity_) return;
        mem_.reset();  // free first: the old and new buffer may not both fit
        capacity_ = 0;
        cl_int status = CL_SUCCESS;
        mem_ = mem_handle(clCreateBuffer(context, flags_, static_cast<std::size_t>(bytes), nullptr, &status));
        check(status, "clCreateBuffer", "allocating " + std::to_string(bytes) + " bytes for " + what_);
        capacity_ = bytes;
    }

    cl_mem get() const { return mem_.get(); }
    std::uint64_t capacity() const { return capacity_; }

private:
    cl_mem_flags flags_;
    std::string what_;
    mem_handle mem_;
    std::uint64_t capacity_ = 0;
};

}  // namespace voxray::opencl_detail
