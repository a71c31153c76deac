// Interop: voxray in the application's own OpenCL context, tracing rays that are already
// in the application's buffers.
//
//   opencl_user_context   the context, device and queue voxray uses (opencl_options::
//                         user_context). voxray retains them while a tracer lives and
//                         releases only those references: the application's own stay valid.
//
// Requirements on the application's side (each checked, with an error naming it):
//   - `device` is one of `context`'s devices; `queue` belongs to that context and device;
//   - the queue is in order (no CL_QUEUE_OUT_OF_ORDER_EXEC_MODE_ENABLE): voxray's uploads
//     and traces rely on its ordering;
//   - ray and hit buffers (cl_mem) belong to `context` and hold at least `count` records.
//     For an offset into a larger buffer, pass a sub-buffer (clCreateSubBuffer; its origin
//     must be a multiple of CL_DEVICE_MEM_BASE_ADDR_ALIGN);
//   - for scenes (staged kernels: two kernels, the second reads the first's hits) the hits
//     buffer is not CL_MEM_WRITE_ONLY.
//
// Synchronisation: tracer::closest_hit / any_hit(cl_mem rays, cl_mem hits, count) enqueue
// the trace kernel (a scene's two) on `queue` and return at once. The queue's order does the
// rest: commands enqueued before it (writing the rays) finish first, commands enqueued after it (reading
// the hits: clEnqueueReadBuffer, the application's kernels) see the hits. Work on other
// queues must wait on that queue (clFinish, or an event of a later marker). update() and the
// host-array trace block until done, as without interop.
//
// Layout: `count` records of 32 bytes in each buffer, exactly core/ray_hit_layout.h (vx_ray
// and vx_hit, i.e. voxray::ray and voxray::hit as bytes). Hit i belongs to ray i.
#pragma once
#include <CL/cl.h>

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "voxray/core/ray_hit_layout.h"
#include "voxray/opencl/error.hpp"

namespace voxray {

struct opencl_user_context {
    cl_context context = nullptr;
    cl_device_id device = nullptr;
    cl_command_queue queue = nullptr;
};

namespace opencl_detail {

// Checks that `mem` can hold `count` records and belongs to `context`; `what` ("rays",
// "hits") names the argument in errors.
inline void check_user_buffer(cl_mem mem, std::size_t count, cl_context context, const char* what) {
    if (!mem) fail("OpenCL: the ", what, " buffer is null");
    cl_context owner = nullptr;
    check(clGetMemObjectInfo(mem, CL_MEM_CONTEXT, sizeof owner, &owner, nullptr), "clGetMemObjectInfo",
          std::string("inspecting the ") + what + " buffer");
    if (owner != context) fail("OpenCL: the ", what, " buffer belongs to another cl_context than the tracer's");
    std::size_t size = 0;
    check(clGetMemObjectInfo(mem, CL_MEM_SIZE, sizeof size, &size, nullptr), "clGetMemObjectInfo",
          std::string("inspecting the ") + what + " buffer");
    std::uint64_t bytes = std::uint64_t(count) * VX_RAY_BYTES;
    if (bytes > size)
        fail("OpenCL: ", count, " ", what, " need ", bytes, " bytes, but the ", what, " buffer holds ", size);
}

// A staged kernel's second stage reads the hits its first wrote: the hits buffer must be
// readable by kernels.
inline void check_readable_hits(cl_mem hits, std::string_view kernel) {
    cl_mem_flags flags = 0;
    check(clGetMemObjectInfo(hits, CL_MEM_FLAGS, sizeof flags, &flags, nullptr), "clGetMemObjectInfo",
          "inspecting the hits buffer");
    if (flags & CL_MEM_WRITE_ONLY)
        fail("OpenCL: the hits buffer is CL_MEM_WRITE_ONLY, but ", kernel,
             " traces in two stages and the second reads the first's hits: create it CL_MEM_READ_WRITE");
}

}  // namespace opencl_detail
}  // namespace voxray
