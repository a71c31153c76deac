// The Vulkan engine for one structure kernel: tracer<vulkan, Structure> holds one.
//
//   upload(blob)                 structure words into a device buffer (grow-only; direct or staged)
//   update_ranges(blob, ranges)  only the changed words, through a commit packet and the
//                                commit shader (vulkan/commit.hpp)
//   trace(...)                   per batch slice: rays in, one dispatch of ceil(n / 64) groups, hits out
//   trace_device / record_trace  rays and hits in the application's buffers (vulkan/interop.hpp)
//
// Synchronous: trace returns when the hits are in the caller's span (record_trace only
// records). Not thread-safe; use one engine per thread.
#pragma once
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

#include <vulkan/vulkan.h>

#include "voxray/core/group_size.hpp"
#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/generated/vulkan_modules.hpp"
#include "voxray/vulkan/buffer.hpp"
#include "voxray/sync/dirty_ranges.hpp"
#include "voxray/sync/upload_plan.hpp"
#include "voxray/vulkan/commands.hpp"
#include "voxray/vulkan/commit.hpp"
#include "voxray/vulkan/device.hpp"
#include "voxray/vulkan/interop.hpp"
#include "voxray/vulkan/kernel_timer.hpp"
#include "voxray/vulkan/options.hpp"
#include "voxray/vulkan/passes.hpp"
#include "voxray/vulkan/pipeline.hpp"
#include "voxray/vulkan/round_trip.hpp"

namespace voxray::vulkan_detail {

// Rays copied, traced and read back per submission: bounds the ray and hit buffers to
// 64 MiB each and one dispatch to 32768 groups (every device allows 65535).
inline constexpr std::size_t max_slice_rays = std::size_t(1) << 21;
// Structure bytes copied per submission when the blob goes through a staging buffer.
inline constexpr VkDeviceSize staging_chunk_bytes = VkDeviceSize(64) << 20;

static_assert(std::is_trivially_copyable_v<ray> && std::is_trivially_copyable_v<hit>,
              "rays and hits are copied to and from device memory as bytes");
static_assert(sizeof(ray) == sizeof(hit), "ray and hit buffers are sized alike");

// The SPIR-V modules of structure kernel `name` (empty spans when it has none).
constexpr spirv_modules find_modules(std::string_view name) {
    for (const spirv_modules& m : registered_modules)
        if (m.name == name) return m;
    return {name, {}};
}

// The trace pipelines' workgroup size: the one asked for (options, VOXRAY_GROUP_SIZE),
// checked against the device's limits, else the default.
inline std::uint32_t trace_group_size(const context& ctx, std::uint32_t asked) {
    std::uint32_t size = requested_group_size(asked);
    if (size == 0) return group_size;
    const auto& limits = ctx.properties().limits;
    std::uint32_t most = std::min(limits.maxComputeWorkGroupSize[0], limits.maxComputeWorkGroupInvocations);
    if (size > most)
        fail("vulkan: a workgroup size of ", size, " was asked for, but ", ctx.name(), " allows at most ", most,
             " (maxComputeWorkGroupSize[0] ", limits.maxComputeWorkGroupSize[0], ", maxComputeWorkGroupInvocations ",
             limits.maxComputeWorkGroupInvocations, ")");
    return size;
}

template <class Kernel>
class engine {
    static constexpr spirv_modules modules_ = find_modules(Kernel::name);
    static_assert(!modules_.trace.empty(),
                  "this structure has no SPIR-V modules: register it with voxray_add_structure (CMake)");

public:
    explicit engine(vulkan_options options)
        : options_(std::move(options)),
          ctx_(shared_context(options_)),
          commands_(std::make_unique<command_stream>(*ctx_)),
          timer_(std::make_unique<kernel_timer>(*ctx_)) {
        group_size_ = trace_group_size(*ctx_, options_.group_size);
        auto start = std::chrono::steady_clock::now();
        closest_ = std::make_unique<compute_pipeline>(*ctx_, modules_.trace, trace_mode{VX_MODE_CLOSEST}, group_size_);
        any_ = std::make_unique<compute_pipeline>(*ctx_, modules_.trace, trace_mode{VX_MODE_ANY}, group_size_);
        pipeline_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        auto groups = std::size_t(ctx_->properties().limits.maxComputeWorkGroupCount[0]);
        slice_ = std::min({max_slice_rays, groups * group_size_, std::size_t(ctx_->max_buffer() / sizeof(ray)),
                           std::size_t(ctx_->max_allocation() / sizeof(ray))});
    }

    engine(engine&&) noexcept = default;
    // Swaps, so that `o` later destroys the old resources in the right order (buffers
    // before the device they belong to); a member-wise move would free the context first.
    engine& operator=(engine&& o) noexcept {
        std::swap(options_, o.options_);
        std::swap(ctx_, o.ctx_);
        std::swap(commands_, o.commands_);
        std::swap(timer_, o.timer_);
        std::swap(kernel_seconds_, o.kernel_seconds_);
        std::swap(closest_, o.closest_);
        std::swap(any_, o.any_);
        std::swap(committer_, o.committer_);
        std::swap(passes_, o.passes_);
        std::swap(blob_, o.blob_);
        std::swap(io_, o.io_);
        std::swap(slice_, o.slice_);
        std::swap(group_size_, o.group_size_);
        std::swap(pipeline_seconds_, o.pipeline_seconds_);
        std::swap(blob_words_, o.blob_words_);
        std::swap(ledger_, o.ledger_);
        return *this;
    }

    void upload(std::span<const std::uint32_t> blob) {
        // Vulkan has no empty buffers; a structure blob always has a header anyway.
        VkDeviceSize bytes = std::max<VkDeviceSize>(blob.size_bytes(), 4);
        if (blob_.size() < bytes) {
            blob_ = buffer();  // free the old one first: both may not fit at once
            blob_ = buffer(*ctx_, bytes, buffer_role::storage_upload, !options_.force_staging, "structure blob");
        }
        blob_words_ = blob.size();
        ledger_.count(blob.size_bytes());
        if (blob_.mapped()) {
            std::memcpy(blob_.mapped(), blob.data(), blob.size_bytes());
            return;  // host writes before vkQueueSubmit are visible to the device
        }
        // Staged: a bounded staging buffer, refilled and copied chunk by chunk.
        VkDeviceSize chunk = std::min(staging_chunk_bytes, bytes);
        buffer staging(*ctx_, chunk, buffer_role::staging_upload, true, "structure staging buffer");
        auto* source = reinterpret_cast<const unsigned char*>(blob.data());
        for (VkDeviceSize done = 0; done < blob.size_bytes(); done += chunk) {
            VkDeviceSize n = std::min<VkDeviceSize>(chunk, blob.size_bytes() - done);
            std::memcpy(staging.mapped(), source + done, n);
            VkCommandBuffer cmd = commands_->begin();
            VkBufferCopy region{0, done, n};
            vkCmdCopyBuffer(cmd, staging.handle(), blob_.handle(), 1, &region);
            // Later submissions' shaders read what the copy wrote.
            command_stream::barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                                    VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
            commands_->submit_and_wait();
        }
    }

    // Sends only the words of `ranges` (any order; overlaps and empty ranges allowed) and
    // runs the commit shader; the next trace sees them. `blob` must have the size last
    // uploaded, else (or when the packet would not be smaller than the blob) the whole
    // blob is uploaded instead.
    void update_ranges(std::span<const std::uint32_t> blob, std::span<const word_range> ranges) {
        auto plan = sync::plan_upload(blob_.handle() ? blob_words_ : 0, blob, ranges);
        if (plan.what == sync::upload_plan::whole) return upload(blob);
        ledger_.count(plan.what == sync::upload_plan::nothing
                          ? 0
                          : committer_.commit(*ctx_, *commands_, blob_, blob, plan.ranges, !options_.force_staging));
    }

    // The blob grew and kept every old word in place (tracer.hpp, grows_in_place): the old
    // words stay on the device (copied there into a larger buffer when this one is too
    // small), the new ones start zero, and only the words of `ranges` are sent.
    void grow_ranges(std::span<const std::uint32_t> blob, std::span<const word_range> ranges) {
        if (!blob_.handle() || blob.size() < blob_words_) return upload(blob);
        VkDeviceSize old_bytes = VkDeviceSize(blob_words_) * sizeof(std::uint32_t), bytes = blob.size_bytes();
        buffer bigger;
        if (blob_.size() < bytes)
            bigger = buffer(*ctx_, bytes, buffer_role::storage_upload, !options_.force_staging, "structure blob");
        buffer& target = bigger.handle() ? bigger : blob_;
        VkCommandBuffer cmd = commands_->begin();
        if (bigger.handle() && old_bytes > 0) {
            VkBufferCopy region{0, 0, old_bytes};
            vkCmdCopyBuffer(cmd, blob_.handle(), bigger.handle(), 1, &region);
        }
        if (bytes > old_bytes) vkCmdFillBuffer(cmd, target.handle(), old_bytes, bytes - old_bytes, 0u);
        // The commit shader and later traces read what the copy and fill wrote.
        command_stream::barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_READ_BIT |
                                    VK_ACCESS_TRANSFER_WRITE_BIT);
        commands_->submit_and_wait();
        if (bigger.handle()) blob_ = std::move(bigger);
        blob_words_ = blob.size();
        update_ranges(blob, ranges);
    }

    // Bytes the last upload or update sent to the device, and their running total.
    std::uint64_t bytes_uploaded_last_update() const { return ledger_.last(); }
    std::uint64_t bytes_uploaded_total() const { return ledger_.total(); }

    // For tests and diagnostics: reads the device blob back (as many words as were last
    // uploaded), to compare word for word with the host's.
    std::vector<std::uint32_t> download_blob() {
        std::vector<std::uint32_t> words(blob_.handle() ? blob_words_ : 0);
        if (words.empty()) return words;
        VkDeviceSize bytes = words.size() * sizeof(std::uint32_t);
        buffer staging;
        if (!blob_.mapped()) staging = buffer(*ctx_, bytes, buffer_role::staging_readback, true, "blob read-back");
        VkCommandBuffer cmd = commands_->begin();
        if (blob_.mapped()) {
            command_stream::barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                                    VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                                    VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
        } else {
            command_stream::barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                                    VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT,
                                    VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
            VkBufferCopy region{0, 0, bytes};
            vkCmdCopyBuffer(cmd, blob_.handle(), staging.handle(), 1, &region);
            command_stream::barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                                    VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
        }
        commands_->submit_and_wait();
        std::memcpy(words.data(), blob_.mapped() ? blob_.mapped() : staging.mapped(), bytes);
        return words;
    }

    void trace(std::span<const ray> rays, std::span<hit> hits, std::uint32_t mode) {
        if (!blob_.handle()) fail("vulkan: trace called before any structure was uploaded");
        if (hits.size() < rays.size()) fail("vulkan: ", rays.size(), " rays but room for only ", hits.size(), " hits");
        kernel_seconds_ = 0;
        for (std::size_t first = 0; first < rays.size(); first += slice_) {
            std::size_t n = std::min(slice_, rays.size() - first);
            trace_slice(rays.subspan(first, n), hits.subspan(first, n), mode);
        }
    }

    // Interop (vulkan/interop.hpp): rays and hits in the application's buffers, traced on
    // its queue; returns when the hits are written. A barrier first makes the writes of
    // earlier work on this queue (the rays) visible to the trace, one after makes the hits
    // visible to later work on this queue and to the host.
    void trace_device(const vulkan_buffer_range& rays, const vulkan_buffer_range& hits, std::size_t count,
                      std::uint32_t mode) {
        auto [in, out] = device_addresses(rays, hits, count);
        if (count == 0) return;
        VkCommandBuffer cmd = commands_->begin();
        command_stream::barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_ACCESS_MEMORY_WRITE_BIT,
                                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                                VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT);
        record_dispatches(cmd, in, out, count, mode);
        command_stream::barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                                VK_PIPELINE_STAGE_ALL_COMMANDS_BIT | VK_PIPELINE_STAGE_HOST_BIT,
                                VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT | VK_ACCESS_HOST_READ_BIT);
        commands_->submit_and_wait();
    }

    // Interop: records the trace into the application's command buffer (in the recording
    // state, for a queue of this device's family) and submits nothing. It binds voxray's
    // pipeline and push constants, and records no barrier: the application orders its ray
    // writes before (to COMPUTE_SHADER / SHADER_READ) and its hit reads after (from
    // COMPUTE_SHADER / SHADER_WRITE). The recording refers to the structure buffer as it
    // is now: re-record after update(), and let it finish before update() or destruction.
    void record_trace(VkCommandBuffer cmd, const vulkan_buffer_range& rays, const vulkan_buffer_range& hits,
                      std::size_t count, std::uint32_t mode) {
        if (!cmd) fail("vulkan: record_trace needs a command buffer, got VK_NULL_HANDLE");
        auto [in, out] = device_addresses(rays, hits, count);
        if (count > 0) record_dispatches(cmd, in, out, count, mode);
    }

    // Frame passes (structures registered with PASSES; world/frame/frame.hpp drives them): a
    // frame buffer of words, host access to it, and one pass run to completion.
    void frame_reserve(std::size_t words) { passes_.reserve(*ctx_, words); }
    void frame_write(std::size_t at, std::span<const std::uint32_t> words) { passes_.write(*ctx_, *commands_, at, words); }
    void frame_read(std::size_t at, std::span<std::uint32_t> words) { passes_.read(*ctx_, *commands_, at, words); }
    void run_pass(std::uint32_t pass, std::uint64_t count)
        requires(!modules_.passes.empty())
    {
        if (!blob_.handle()) fail("vulkan: a frame pass ran before any structure was uploaded");
        if (count > 0) passes_.run(*ctx_, *commands_, modules_.passes, blob_.address(), pass, count);
    }
    // Bytes of device memory the frame buffer holds.
    std::uint64_t frame_bytes() const { return passes_.bytes(); }

    std::string device_name() const { return ctx_->name(); }
    // The logical device this tracer runs on (shared with every tracer on that device).
    VkDevice device() const { return ctx_->device(); }
    // Type, limits (maxStorageBufferRange...) and API version of the device in use.
    const VkPhysicalDeviceProperties& device_properties() const { return ctx_->properties(); }
    // True when some buffer is reached through staging copies (discrete GPUs, or
    // vulkan_options::force_staging) rather than mapped directly.
    bool uses_staging() const {
        return (blob_.handle() && !blob_.mapped()) || io_.uses_staging();
    }
    // Device seconds the dispatches of the last trace() took, copies of rays and hits left
    // out (GPU timestamps); NaN where the queue has none.
    double kernel_seconds_last_trace() const { return kernel_seconds_; }
    // Invocations per workgroup of the trace pipelines (vulkan_options::group_size).
    std::uint32_t work_group_size() const { return group_size_; }
    // Seconds spent creating the compute pipeline (driver compiles SPIR-V to machine code).
    double pipeline_seconds() const { return pipeline_seconds_; }

private:

    // Grow-only ray/hit buffers (and their staging twins where they are not mapped).
    void reserve(std::size_t count) {
        io_.reserve_records(*ctx_, count, slice_, sizeof(ray), sizeof(hit), !options_.force_staging, "ray buffer",
                            "hit buffer");
    }

    void trace_slice(std::span<const ray> rays, std::span<hit> hits, std::uint32_t mode) {
        reserve(rays.size());
        VkCommandBuffer cmd = commands_->begin();
        io_.write_inputs(cmd, rays.data(), rays.size_bytes());
        timer_->start(cmd);
        record_dispatches(cmd, io_.input_address(), io_.output_address(), rays.size(), mode);
        timer_->stop(cmd);
        io_.record_read_back(cmd, hits.size_bytes());
        commands_->submit_and_wait();
        kernel_seconds_ += timer_->seconds();
        io_.read_outputs(hits.data(), hits.size_bytes());
    }

    // One dispatch per maxComputeWorkGroupCount groups; the addresses advance between them.
    void record_dispatches(VkCommandBuffer cmd, VkDeviceAddress rays, VkDeviceAddress hits, std::size_t count,
                           std::uint32_t mode) {
        std::size_t per = std::size_t(ctx_->properties().limits.maxComputeWorkGroupCount[0]) * group_size_;
        for (std::size_t first = 0; first < count; first += per) {
            std::size_t n = std::min(per, count - first);
            push_constants pc{blob_.address(), rays + first * sizeof(ray), hits + first * sizeof(hit),
                              std::uint32_t(n), 0};
            (mode == VX_MODE_ANY ? any_ : closest_)->bind(cmd, pc);
            vkCmdDispatch(cmd, std::uint32_t((n + group_size_ - 1) / group_size_), 1, 1);
        }
    }

    std::pair<VkDeviceAddress, VkDeviceAddress> device_addresses(const vulkan_buffer_range& rays,
                                                                 const vulkan_buffer_range& hits, std::size_t count) {
        if (!blob_.handle()) fail("vulkan: trace called before any structure was uploaded");
        return {record_address(ctx_->device(), rays, count, "rays"), record_address(ctx_->device(), hits, count, "hits")};
    }

    vulkan_options options_;
    // Declaration order is destruction order reversed: the context goes last.
    std::shared_ptr<context> ctx_;  // shared with the other tracers on this device
    std::unique_ptr<command_stream> commands_;
    std::unique_ptr<kernel_timer> timer_;
    std::unique_ptr<compute_pipeline> closest_, any_;  // one pipeline per trace mode, one module
    committer committer_;
    pass_runner passes_;
    buffer blob_;
    round_trip_buffers io_;  // rays in, hits out
    std::size_t slice_ = max_slice_rays;
    std::uint32_t group_size_ = group_size;  // invocations per workgroup of the trace pipelines
    double pipeline_seconds_ = 0;
    double kernel_seconds_ = 0;  // of the last trace()
    std::size_t blob_words_ = 0;
    sync::upload_ledger ledger_;
};

}  // namespace voxray::vulkan_detail
