// What a backend must offer tracer<Backend, Structure>, written as concepts: the one place
// that says it. tracer<Backend, Structure> checks every engine it is made with against
// trace_engine, and its error names the requirement that is unmet; the optional parts
// are used where an engine meets them.
//
//   backend           B::options, B::name, and B::engine<Kernel> for each structure kernel
//   trace_engine      upload a blob, send word ranges of it, trace rays into hits,
//                     count the bytes sent, read the blob back (tests, diagnostics)
//   growing_engine    + grow_ranges: keep the old words when the blob grows at its end
//   device_engine     + trace_device: rays and hits in the application's device buffers
//   pass_engine       + the frame passes on the device (world/frame.hpp): a frame buffer
//                     to reserve, write, read and size, and run_pass
//   timed_engine      + kernel_seconds_last_trace: the device time of the last trace's
//                     kernels alone, without copies of rays and hits (NaN: unknown)
// An engine without the optional parts still traces: the tracer sends a grown blob
// whole, has no device-buffer overloads, and runs frame passes on the CPU.
#pragma once
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/core/word_range.hpp"

namespace voxray {

template <class E>
concept trace_engine = requires(E& e, const E& c, std::span<const std::uint32_t> blob,
                                std::span<const word_range> ranges, std::span<const ray> rays, std::span<hit> hits,
                                std::uint32_t mode) {
    e.upload(blob);
    e.update_ranges(blob, ranges);
    e.trace(rays, hits, mode);
    { c.bytes_uploaded_last_update() } -> std::convertible_to<std::uint64_t>;
    { c.bytes_uploaded_total() } -> std::convertible_to<std::uint64_t>;
    { e.download_blob() } -> std::convertible_to<std::vector<std::uint32_t>>;  // may submit work: not const
};

template <class E>
concept growing_engine = trace_engine<E> && requires(E& e, std::span<const std::uint32_t> blob,
                                                     std::span<const word_range> ranges) {
    e.grow_ranges(blob, ranges);
};

// DeviceBuffer: the backend's own handle of an application buffer (cl_mem, vulkan_buffer_range).
template <class E, class DeviceBuffer>
concept device_engine = trace_engine<E> && requires(E& e, const DeviceBuffer& b, std::size_t count, std::uint32_t mode) {
    e.trace_device(b, b, count, mode);
};

template <class E>
concept pass_engine = trace_engine<E> && requires(E& e, std::size_t at, std::span<const std::uint32_t> in,
                                                  std::span<std::uint32_t> out, std::uint32_t pass, std::uint64_t items) {
    e.frame_reserve(at);
    e.frame_write(at, in);
    e.frame_read(at, out);
    e.run_pass(pass, items);
    { e.frame_bytes() } -> std::convertible_to<std::uint64_t>;
};

template <class B>
concept backend = requires {
    typename B::options;
    { B::name } -> std::convertible_to<const char*>;
};

template <class E>
concept timed_engine = trace_engine<E> && requires(const E& c) {
    { c.kernel_seconds_last_trace() } -> std::convertible_to<double>;
};

}  // namespace voxray
