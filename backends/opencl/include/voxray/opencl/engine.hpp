// The OpenCL engine for one structure kernel: the blob lives in one device buffer, rays
// and hits go through two more that are reused while they are big enough. Edits reach
// the device blob through update_ranges (opencl/commit.hpp). trace_device traces rays
// already in the application's buffers (opencl/interop.hpp). One engine per thread: an
// engine's kernel arguments and buffers are not guarded.
#pragma once
#include <CL/cl.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "voxray/core/group_size.hpp"
#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/opencl/buffer.hpp"
#include "voxray/opencl/commit.hpp"
#include "voxray/opencl/interop.hpp"
#include "voxray/opencl/launch.hpp"
#include "voxray/opencl/passes.hpp"
#include "voxray/opencl/program_cache.hpp"
#include "voxray/sync/dirty_ranges.hpp"
#include "voxray/sync/upload_plan.hpp"

namespace voxray::opencl_detail {

// The embedded program of structure kernel `name` (a null source when it has none).
constexpr program_source find_program(std::string_view name) {
    for (const program_source& p : registered_programs)
        if (p.name == name) return p;
    return {name, nullptr};
}

// Whether kernel `name` has an embedded program. By name, not by comparing the source's
// address with null: g++ with -fsanitize=address does not fold an extern array's address
// in a constant expression, and the ASan build would not compile.
constexpr bool has_program(std::string_view name) {
    for (const program_source& p : registered_programs)
        if (p.name == name) return true;
    return false;
}

template <class Kernel>
class opencl_engine {
    static constexpr program_source program_ = find_program(Kernel::name);
    static_assert(has_program(Kernel::name),
                  "this structure has no OpenCL program: register it with voxray_add_structure (CMake)");

public:
    explicit opencl_engine(opencl_options options) : ctx_(acquire_device_context(options)), committer_(ctx_) {
        if (options.user_context) {
            // The application's queue (checked by acquire_device_context): retained, so
            // that releasing ours leaves the application's reference alone.
            check(clRetainCommandQueue(options.user_context->queue), "clRetainCommandQueue", "the application's queue");
            queue_ = queue_handle(options.user_context->queue);
        } else {
            // Profiling on: kernel_seconds_last_trace() reads the trace kernels' device time.
            cl_int status = CL_SUCCESS;
            queue_ = queue_handle(
                clCreateCommandQueue(ctx_->context(), ctx_->device(), CL_QUEUE_PROFILING_ENABLE, &status));
            check(status, "clCreateCommandQueue", "opening device '" + ctx_->device_name() + "'");
        }
        cl_command_queue_properties queue_properties = 0;
        check(clGetCommandQueueInfo(queue_.get(), CL_QUEUE_PROPERTIES, sizeof queue_properties, &queue_properties,
                                    nullptr),
              "clGetCommandQueueInfo", "reading the queue's properties");
        profiling_ = (queue_properties & CL_QUEUE_PROFILING_ENABLE) != 0;
        cl_program program = ctx_->program(program_);
        closest_ = create_kernel(program, std::string("vx_closest_") + Kernel::name);
        any_ = create_kernel(program, std::string("vx_any_") + Kernel::name);
        if (program_.staged) {
            closest_then_ = create_kernel(program, std::string("vx_closest_") + Kernel::name + "_then");
            any_then_ = create_kernel(program, std::string("vx_any_") + Kernel::name + "_then");
        }
        // The kernels come from one source; the smallest limit serves them all.
        local_size_ = std::numeric_limits<std::size_t>::max();
        std::size_t most = std::numeric_limits<std::size_t>::max();
        for (cl_kernel k : {closest_.get(), any_.get(), closest_then_.get(), any_then_.get()})
            if (k) {
                local_size_ = std::min(local_size_, group_size_for(k, ctx_->device()));
                most = std::min(most, kernel_group_limit(k, ctx_->device()));
            }
        if (std::size_t asked = requested_group_size(options.group_size)) {
            if (asked > most)
                fail("OpenCL: a work-group size of ", asked, " was asked for, but the trace kernels of ", Kernel::name,
                     " allow at most ", most, " on '", ctx_->device_name(), "' (CL_KERNEL_WORK_GROUP_SIZE)");
            local_size_ = asked;
        }
    }

    // Copies the blob to the device (blocking: the caller's span may die right after).
    void upload(std::span<const std::uint32_t> blob) {
        if (blob.empty()) fail("OpenCL: cannot upload an empty structure blob");
        std::uint64_t bytes = std::uint64_t(blob.size()) * sizeof(std::uint32_t);
        check_alloc_limit("the structure blob", bytes, ctx_->max_alloc_bytes(), ctx_->device_name());
        blob_.reserve(ctx_->context(), bytes);
        check(clEnqueueWriteBuffer(queue_.get(), blob_.get(), CL_TRUE, 0, static_cast<std::size_t>(bytes),
                                   blob.data(), 0, nullptr, nullptr),
              "clEnqueueWriteBuffer", "uploading the structure blob");
        uploaded_ = true;
        blob_words_ = blob.size();
        ledger_.count(bytes);
    }

    // Sends the whole blob again.
    void update(std::span<const std::uint32_t> blob) { upload(blob); }

    // Sends only the words of `ranges` (any order; overlaps and empty ranges allowed),
    // through one commit packet and the commit kernel. `blob` must have the size last
    // uploaded, else (or when the packet would not be smaller than the blob) the whole
    // blob is uploaded instead.
    void update_ranges(std::span<const std::uint32_t> blob, std::span<const word_range> ranges) {
        auto plan = sync::plan_upload(uploaded_ ? blob_words_ : 0, blob, ranges);
        if (plan.what == sync::upload_plan::whole) return upload(blob);
        ledger_.count(plan.what == sync::upload_plan::nothing ? 0 : committer_.commit(queue_.get(), blob_.get(), blob, plan.ranges));
    }

    // The blob grew and kept every old word in place (tracer.hpp, grows_in_place): the old
    // words stay on the device (copied there into a larger buffer when this one is too
    // small), the new ones start zero, and only the words of `ranges` are sent.
    void grow_ranges(std::span<const std::uint32_t> blob, std::span<const word_range> ranges) {
        if (!uploaded_ || blob.size() < blob_words_) return upload(blob);
        std::uint64_t old_bytes = std::uint64_t(blob_words_) * sizeof(std::uint32_t);
        std::uint64_t bytes = std::uint64_t(blob.size()) * sizeof(std::uint32_t);
        check_alloc_limit("the structure blob", bytes, ctx_->max_alloc_bytes(), ctx_->device_name());
        if (blob_.capacity() < bytes) {
            device_buffer bigger{CL_MEM_READ_WRITE, "the structure blob"};
            bigger.reserve(ctx_->context(), bytes);
            check(clEnqueueCopyBuffer(queue_.get(), blob_.get(), bigger.get(), 0, 0, static_cast<std::size_t>(old_bytes), 0,
                                      nullptr, nullptr),
                  "clEnqueueCopyBuffer", "keeping the structure blob's words in a larger buffer");
            std::swap(blob_, bigger);  // OpenCL keeps the old buffer alive until the copy is done
        }
        if (bytes > old_bytes) {
            const cl_uint zero = 0;
            check(clEnqueueFillBuffer(queue_.get(), blob_.get(), &zero, sizeof zero, static_cast<std::size_t>(old_bytes),
                                      static_cast<std::size_t>(bytes - old_bytes), 0, nullptr, nullptr),
                  "clEnqueueFillBuffer", "zeroing the structure blob's new words");
        }
        blob_words_ = blob.size();
        update_ranges(blob, ranges);
    }

    // Bytes the last upload or update sent to the device, and their running total.
    std::uint64_t bytes_uploaded_last_update() const { return ledger_.last(); }
    std::uint64_t bytes_uploaded_total() const { return ledger_.total(); }

    // For tests and diagnostics: reads the device blob back (as many words as were last
    // uploaded), to compare word for word with the host's.
    std::vector<std::uint32_t> download_blob() {
        std::vector<std::uint32_t> words(uploaded_ ? blob_words_ : 0);
        if (words.empty()) return words;
        check(clEnqueueReadBuffer(queue_.get(), blob_.get(), CL_TRUE, 0, words.size() * sizeof(std::uint32_t),
                                  words.data(), 0, nullptr, nullptr),
              "clEnqueueReadBuffer", "reading the structure blob back");
        return words;
    }

    void trace(std::span<const ray> rays, std::span<hit> hits, std::uint32_t mode) {
        if (hits.size() < rays.size())
            fail("OpenCL: ", rays.size(), " rays but room for only ", hits.size(), " hits");
        kernel_seconds_ = profiling_ ? 0.0 : NAN;
        if (rays.empty()) return;
        if (!uploaded_) fail("OpenCL: trace before any structure was uploaded");

        // Rays go in batches that fit one allocation and a 32-bit count (a real limit
        // only on small devices; one batch everywhere else).
        std::uint64_t batch = std::min<std::uint64_t>(rays.size(), ctx_->max_alloc_bytes() / VX_HIT_BYTES);
        batch = std::min<std::uint64_t>(batch, std::numeric_limits<cl_uint>::max() - local_size_);
        if (batch == 0) fail("OpenCL: device '", ctx_->device_name(), "' cannot allocate even one ray record");
        rays_.reserve(ctx_->context(), batch * VX_RAY_BYTES);
        hits_.reserve(ctx_->context(), batch * VX_HIT_BYTES);

        for (std::size_t first = 0; first < rays.size(); first += batch) {
            cl_uint count = static_cast<cl_uint>(std::min<std::uint64_t>(batch, rays.size() - first));
            // Blocking write: if a later call throws, no transfer still points at the
            // caller's rays. The kernel would wait for the copy anyway.
            check(clEnqueueWriteBuffer(queue_.get(), rays_.get(), CL_TRUE, 0, std::size_t(count) * VX_RAY_BYTES,
                                       rays.data() + first, 0, nullptr, nullptr),
                  "clEnqueueWriteBuffer", "sending rays");
            event_handle done[2];
            enqueue_trace(rays_.get(), hits_.get(), count, mode, profiling_ ? done : nullptr);
            check(clEnqueueReadBuffer(queue_.get(), hits_.get(), CL_TRUE, 0, std::size_t(count) * VX_HIT_BYTES,
                                      hits.data() + first, 0, nullptr, nullptr),
                  "clEnqueueReadBuffer", "reading hits");
            for (auto& d : done)  // complete: the read came after them
                if (d) kernel_seconds_ += event_seconds(d.get());
        }
    }

    // Device seconds the trace kernels of the last trace() took, copies of rays and hits
    // left out (profiling events); NaN where the queue does not profile (an application's).
    double kernel_seconds_last_trace() const { return kernel_seconds_; }

    // Interop (opencl/interop.hpp): rays and hits in the application's buffers. Enqueues
    // the kernel on the queue and returns; the in-order queue orders it after the commands
    // before it and before those after it.
    void trace_device(cl_mem rays, cl_mem hits, std::size_t count, std::uint32_t mode) {
        if (!uploaded_) fail("OpenCL: trace before any structure was uploaded");
        check_user_buffer(rays, count, ctx_->context(), "rays");
        check_user_buffer(hits, count, ctx_->context(), "hits");
        if (program_.staged) check_readable_hits(hits, Kernel::name);
        if (count > std::numeric_limits<cl_uint>::max() - local_size_)
            fail("OpenCL: ", count, " rays in one trace, more than the kernel's 32-bit count allows; split them");
        if (count > 0) enqueue_trace(rays, hits, cl_uint(count), mode);
    }

    // Frame passes (structures registered with PASSES; world/frame/frame.hpp drives them):
    // a pass_runner (opencl/passes.hpp) on this engine's device, queue, program and blob.
    // The kernel is vx_pass_<name> in the structure's program.
    void frame_reserve(std::size_t words) { passes_.reserve(*ctx_, words); }
    void frame_write(std::size_t at, std::span<const std::uint32_t> words) { passes_.write(queue_.get(), at, words); }
    void frame_read(std::size_t at, std::span<std::uint32_t> words) { passes_.read(queue_.get(), at, words); }
    void run_pass(std::uint32_t pass, std::uint64_t count) {
        if (!uploaded_) fail("OpenCL: a frame pass ran before any structure was uploaded");
        passes_.run(*ctx_, queue_.get(), ctx_->program(program_), std::string("vx_pass_") + Kernel::name, blob_.get(),
                    pass, count, local_size_);
    }
    std::uint64_t frame_bytes() const { return passes_.bytes(); }

    std::string device_name() const { return ctx_->device_name(); }
    std::string platform_name() const { return ctx_->platform_name(); }
    // Seconds this structure's program took to build (once per device and process).
    double program_build_seconds() const { return ctx_->build_seconds(program_.name); }
    bool correctly_rounded_division() const { return ctx_->correctly_rounded_division(); }
    std::uint64_t max_alloc_bytes() const { return ctx_->max_alloc_bytes(); }
    std::size_t work_group_size() const { return local_size_; }

private:
    // The trace kernel of `mode`, then, for a staged kernel, its second stage on the same
    // hits (the in-order queue runs it after the first). `done`: an event per kernel.
    // Kernel arguments are captured at enqueue time, so the kernel objects are free for
    // the next call at once.
    void enqueue_trace(cl_mem in, cl_mem out, cl_uint count, std::uint32_t mode, event_handle* done = nullptr) {
        bool any = mode == VX_MODE_ANY;
        enqueue_kernel(any ? any_.get() : closest_.get(), in, out, count, done);
        if (program_.staged)
            enqueue_kernel(any ? any_then_.get() : closest_then_.get(), in, out, count, done ? done + 1 : nullptr);
    }
    void enqueue_kernel(cl_kernel kernel, cl_mem in, cl_mem out, cl_uint count, event_handle* done) {
        cl_mem blob = blob_.get();
        check(clSetKernelArg(kernel, 0, sizeof blob, &blob), "clSetKernelArg", "setting the blob");
        check(clSetKernelArg(kernel, 1, sizeof in, &in), "clSetKernelArg", "setting the rays");
        check(clSetKernelArg(kernel, 2, sizeof out, &out), "clSetKernelArg", "setting the hits");
        check(clSetKernelArg(kernel, 3, sizeof count, &count), "clSetKernelArg", "setting the count");
        // The global size is rounded up to whole groups; the kernel skips the extra items.
        std::size_t global = (std::size_t(count) + local_size_ - 1) / local_size_ * local_size_;
        cl_event event = nullptr;
        check(clEnqueueNDRangeKernel(queue_.get(), kernel, 1, nullptr, &global, &local_size_, 0, nullptr,
                                     done ? &event : nullptr),
              "clEnqueueNDRangeKernel", "tracing " + std::to_string(count) + " rays");
        if (done) *done = event_handle(event);
    }

    // Start to end of a completed command on a profiling queue.
    static double event_seconds(cl_event event) {
        cl_ulong start = 0, end = 0;
        check(clGetEventProfilingInfo(event, CL_PROFILING_COMMAND_START, sizeof start, &start, nullptr),
              "clGetEventProfilingInfo", "reading a trace's start time");
        check(clGetEventProfilingInfo(event, CL_PROFILING_COMMAND_END, sizeof end, &end, nullptr),
              "clGetEventProfilingInfo", "reading a trace's end time");
        return double(end - start) * 1e-9;
    }

    std::shared_ptr<device_context> ctx_;
    queue_handle queue_;
    kernel_handle closest_, any_;
    kernel_handle closest_then_, any_then_;  // a staged kernel's second stage (entry.cl)
    committer committer_;
    // Read-write: the commit kernel writes it; the trace kernels only read it.
    device_buffer blob_{CL_MEM_READ_WRITE, "the structure blob"};
    device_buffer rays_{CL_MEM_READ_ONLY, "rays"};
    device_buffer hits_{CL_MEM_READ_WRITE, "hits"};  // a staged kernel's second stage reads them
    pass_runner passes_;
    std::size_t local_size_ = 1;
    bool uploaded_ = false;
    bool profiling_ = false;     // the queue records command times
    double kernel_seconds_ = 0;  // of the last trace()
    std::size_t blob_words_ = 0;
    sync::upload_ledger ledger_;
};

}  // namespace voxray::opencl_detail
