// Error translation for the OpenCL backend: every cl* call goes through check(), which
// turns a failure into a voxray::opencl_error naming the call and the CL status by name,
// so that a user reading "clEnqueueNDRangeKernel failed: CL_OUT_OF_RESOURCES (-5)"
// knows what went wrong without the CL headers at hand.
#pragma once
#include <CL/cl.h>

#include <string>

#include "voxray/core/error.hpp"

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
inline const char* cl_status_name(cl_int code) {
    switch (code) {
#define VX_CL_STATUS(name) case name: return #name;
        VX_CL_STATUS(CL_SUCCESS)
        VX_CL_STATUS(CL_DEVICE_NOT_FOUND)
        VX_CL_STATUS(CL_DEVICE_NOT_AVAILABLE)
        VX_CL_STATUS(CL_COMPILER_NOT_AVAILABLE)
        VX_CL_STATUS(CL_MEM_OBJECT_ALLOCATION_FAILURE)
        VX_CL_STATUS(CL_OUT_OF_RESOURCES)
        VX_CL_STATUS(CL_OUT_OF_HOST_MEMORY)
        VX_CL_STATUS(CL_PROFILING_INFO_NOT_AVAILABLE)
        VX_CL_STATUS(CL_MEM_COPY_OVERLAP)
        VX_CL_STATUS(CL_IMAGE_FORMAT_MISMATCH)
        VX_CL_STATUS(CL_IMAGE_FORMAT_NOT_SUPPORTED)
        VX_CL_STATUS(CL_BUILD_PROGRAM_FAILURE)
        VX_CL_STATUS(CL_MAP_FAILURE)
        VX_CL_STATUS(CL_MISALIGNED_SUB_BUFFER_OFFSET)
        VX_CL_STATUS(CL_EXEC_STATUS_ERROR_FOR_EVENTS_IN_WAIT_LIST)
        VX_CL_STATUS(CL_COMPILE_PROGRAM_FAILURE)
        VX_CL_STATUS(CL_LINKER_NOT_AVAILABLE)
        VX_CL_STATUS(CL_LINK_PROGRAM_FAILURE)
        VX_CL_STATUS(CL_DEVICE_PARTITION_FAILED)
        VX_CL_STATUS(CL_KERNEL_ARG_INFO_NOT_AVAILABLE)
        VX_CL_STATUS(CL_INVALID_VALUE)
        VX_CL_STATUS(CL_INVALID_DEVICE_TYPE)
        VX_CL_STATUS(CL_INVALID_PLATFORM)
        VX_CL_STATUS(CL_INVALID_DEVICE)
        VX_CL_STATUS(CL_INVALID_CONTEXT)
        VX_CL_STATUS(CL_INVALID_QUEUE_PROPERTIES)
        VX_CL_STATUS(CL_INVALID_COMMAND_QUEUE)
        VX_CL_STATUS(CL_INVALID_HOST_PTR)
        VX_CL_STATUS(CL_INVALID_MEM_OBJECT)
        VX_CL_STATUS(CL_INVALID_IMAGE_FORMAT_DESCRIPTOR)
        VX_CL_STATUS(CL_INVALID_IMAGE_SIZE)
        VX_CL_STATUS(CL_INVALID_SAMPLER)
        VX_CL_STATUS(CL_INVALID_BINARY)
        VX_CL_STATUS(CL_INVALID_BUILD_OPTIONS)
        VX_CL_STATUS(CL_INVALID_PROGRAM)
        VX_CL_STATUS(CL_INVALID_PROGRAM_EXECUTABLE)
        VX_CL_STATUS(CL_INVALID_KERNEL_NAME)
        VX_CL_STATUS(CL_INVALID_KERNEL_DEFINITION)
        VX_CL_STATUS(CL_INVALID_KERNEL)
        VX_CL_STATUS(CL_INVALID_ARG_INDEX)
        VX_CL_STATUS(CL_INVALID_ARG_VALUE)
        VX_CL_STATUS(CL_INVALID_ARG_SIZE)
        VX_CL_STATUS(CL_INVALID_KERNEL_ARGS)
        VX_CL_STATUS(CL_INVALID_WORK_DIMENSION)
        VX_CL_STATUS(CL_INVALID_WORK_GROUP_SIZE)
        VX_CL_STATUS(CL_INVALID_WORK_ITEM_SIZE)
        VX_CL_STATUS(CL_INVALID_GLOBAL_OFFSET)
        VX_CL_STATUS(CL_INVALID_EVENT_WAIT_LIST)
        VX_CL_STATUS(CL_INVALID_EVENT)
        VX_CL_STATUS(CL_INVALID_OPERATION)
        VX_CL_STATUS(CL_INVALID_GL_OBJECT)
        VX_CL_STATUS(CL_INVALID_BUFFER_SIZE)
        VX_CL_STATUS(CL_INVALID_MIP_LEVEL)
        VX_CL_STATUS(CL_INVALID_GLOBAL_WORK_SIZE)
        VX_CL_STATUS(CL_INVALID_PROPERTY)
        VX_CL_STATUS(CL_INVALID_IMAGE_DESCRIPTOR)
        VX_CL_STATUS(CL_INVALID_COMPILER_OPTIONS)
        VX_CL_STATUS(CL_INVALID_LINKER_OPTIONS)
        VX_CL_STATUS(CL_INVALID_DEVICE_PARTITION_COUNT)
#undef VX_CL_STATUS
    case -1001: return "CL_PLATFORM_NOT_FOUND_KHR";  // ICD loader: no platform installed
    default: return "unknown OpenCL status";
    }
}

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
