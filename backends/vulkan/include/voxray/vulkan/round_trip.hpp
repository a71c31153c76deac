// Device buffers for one round trip of records: the host writes inputs (rays), dispatches
// read them and write outputs (hits, pixels), the host reads those back. Grow-only, each with
// a staging twin where it is not mapped (discrete GPUs, vulkan_options::force_staging). The
// tracer's engine (engine.hpp) and the appearance walker (appearance_walk.hpp) share it.
//
//   reserve(ctx, in_bytes, out_bytes, ...)   before recording (or reserve_records)
//   write_inputs(cmd, data, bytes)           copies in; records the staging copy if any
//   ... dispatches over input_address() and output_address() ...
//   record_read_back(cmd, bytes)             the barrier (and copy) the host read needs
//   submit and wait, then read_outputs(to, bytes)
#pragma once
#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstring>

#include <vulkan/vulkan.h>

#include "voxray/vulkan/buffer.hpp"
#include "voxray/vulkan/commands.hpp"
#include "voxray/vulkan/device.hpp"

namespace voxray::vulkan_detail {

class round_trip_buffers {
public:
    VkDeviceSize input_bytes() const { return in_.size(); }  // 0 before the first reserve
    VkDeviceSize output_bytes() const { return out_.size(); }
    VkDeviceAddress input_address() const { return in_.address(); }
    VkDeviceAddress output_address() const { return out_.address(); }
    bool uses_staging() const { return (in_.handle() && !in_.mapped()) || (out_.handle() && !out_.mapped()); }

    // Room for `in_bytes` of inputs and `out_bytes` of outputs. Keeps the buffers it has where
    // both fit; else frees them first (their contents are dropped) and makes new ones, all or
    // nothing: an input buffer without its output buffer must not look ready.
    void reserve(const context& ctx, VkDeviceSize in_bytes, VkDeviceSize out_bytes, bool mapped, const char* in_what,
                 const char* out_what) {
        if (in_.handle() && in_.size() >= in_bytes && out_.size() >= out_bytes) return;
        in_bytes = std::max(in_bytes, in_.size()), out_bytes = std::max(out_bytes, out_.size());
        *this = round_trip_buffers();
        try {
            in_ = buffer(ctx, in_bytes, buffer_role::storage_upload, mapped, in_what);
            out_ = buffer(ctx, out_bytes, buffer_role::storage_readback, mapped, out_what);
            if (!in_.mapped()) in_staging_ = buffer(ctx, in_bytes, buffer_role::staging_upload, true, in_what);
            if (!out_.mapped()) out_staging_ = buffer(ctx, out_bytes, buffer_role::staging_readback, true, out_what);
        } catch (...) {
            *this = round_trip_buffers();
            throw;
        }
    }

    // Room for `count` records of `in_record` and `out_record` bytes: where the inputs do not
    // fit, grows to the next power of two records, at most `slice` (a submission's most).
    void reserve_records(const context& ctx, std::size_t count, std::size_t slice, std::size_t in_record,
                         std::size_t out_record, bool mapped, const char* in_what, const char* out_what) {
        if (in_.size() >= count * in_record) return;
        std::size_t capacity = std::min(slice, std::bit_ceil(count));
        reserve(ctx, capacity * in_record, capacity * out_record, mapped, in_what, out_what);
    }

    // Copies `bytes` of inputs in. Host writes before vkQueueSubmit are visible to the device;
    // through a staging buffer, `cmd` gets the copy and the barrier before the dispatches.
    void write_inputs(VkCommandBuffer cmd, const void* data, VkDeviceSize bytes) const {
        std::memcpy(in_.mapped() ? in_.mapped() : in_staging_.mapped(), data, bytes);
        if (in_.mapped()) return;
        VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, in_staging_.handle(), in_.handle(), 1, &region);
        command_stream::barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
    }

    // After the dispatches: the barrier that makes shader writes visible to the host
    // (directly, or after the copy of `bytes` into the staging buffer).
    void record_read_back(VkCommandBuffer cmd, VkDeviceSize bytes) const {
        if (out_.mapped()) {
            command_stream::barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                                    VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
            return;
        }
        command_stream::barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                                VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_READ_BIT);
        VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, out_.handle(), out_staging_.handle(), 1, &region);
        command_stream::barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    }

    // Once the submission has finished.
    void read_outputs(void* to, VkDeviceSize bytes) const {
        std::memcpy(to, out_.mapped() ? out_.mapped() : out_staging_.mapped(), bytes);
    }

private:
    buffer in_, out_, in_staging_, out_staging_;
};

}  // namespace voxray::vulkan_detail
