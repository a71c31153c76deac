// Error translation for the OpenCL backend: every cl* call goes through check(), which
// turns a failure into a voxray::opencl_error naming the call and the CL status by name,
// so that a user reading "clEnqueueNDRangeKernel failed: CL_OUT_OF_RESOURCES (-5)"
// knows what went wrong without the CL headers at hand.
#pragma once
#include <CL/cl.h>

#include <string>

#include "voxray/core/error.hpp"
#include "voxray/core/host_code.hpp"

namespace voxray {

// Also a voxray::error, so callers that catch the library's one type see it too; the
// code is kept for those that want to react to a particular status.
class opencl_error : public error {
public:
    opencl_error(const std::string& message, cl_int code) : error(message), code_(code) {}
    cl_int code() const { return code_; }

private:
    cl_int code_;
};

namespace opencl_detail {

// Names of the OpenCL 1.2 status codes, plus the ICD loader's "no platform" code.
VOXRAY_HOST_INLINE const char* cl_status_name(cl_int code);

// Throws opencl_error unless `status` is CL_SUCCESS. `call` names the failed function
// and `context` (optional) says what it was doing, e.g. "uploading the structure".
inline void check(cl_int status, const char* call, const std::string& context = {}) {
    if (status == CL_SUCCESS) return;
    std::string message = std::string("OpenCL: ") + call + " failed: " + cl_status_name(status) + " (" +
                          std::to_string(status) + ")";
    if (!context.empty()) message += " while " + context;
    throw opencl_error(message, status);
}

}  // namespace opencl_detail
}  // namespace voxray

// The definitions: here, or compiled once in voxray::kernels (core/host_code.hpp).
#if VOXRAY_HOST_DEFINITIONS
#include "voxray/opencl/detail/error.hpp"
#endif
