// The compositing walk (appearance/walk.inc) on a Vulkan device, for any structure kernel:
// the module <structure>_appearance (voxray_add_appearance_walk) as one pipeline with push
// constants only, like the trace shaders. The structure and its appearance table are
// uploaded once; each walk sends rays and reads pixels through buffers it keeps (grow-only,
// vulkan/round_trip.hpp). Same arguments and results as the CPU walker
// (cpu/appearance_walk.hpp): the pixels agree bit for bit (tests/appearance).
//
//   voxray::vulkan_appearance_walker<voxray::kernels::dense_grid_kernel> walker(blob, table);
//   std::vector<voxray::appearance_pixel> out = walker.walk(rays, light);
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#if !defined(VOXRAY_LINKED_VULKAN)
#error "voxray/vulkan/appearance_walk.hpp needs voxray::vulkan: link it"
#endif
#include "voxray/appearance/walk_inputs.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/vulkan/buffer.hpp"
#include "voxray/vulkan/commands.hpp"
#include "voxray/vulkan/device.hpp"
#include "voxray/vulkan/engine.hpp"
#include "voxray/vulkan/options.hpp"
#include "voxray/vulkan/pipeline.hpp"
#include "voxray/vulkan/round_trip.hpp"

namespace voxray::vulkan_detail {

// Must match the push constant block of backends/vulkan/shaders/appearance_entry.glsl.
struct appearance_push {
    std::uint64_t blob, index, records, faces, rays, pixels;
    float to_light[3];
    float ambient;
    float cutoff;
    std::uint32_t max_visits;
    std::uint32_t kind;
    std::uint32_t count;
    std::uint32_t shadows_at;
};
static_assert(sizeof(appearance_push) == 88 && offsetof(appearance_push, to_light) == 48);
static_assert(offsetof(appearance_push, cutoff) == 64 && offsetof(appearance_push, shadows_at) == 80);

}  // namespace voxray::vulkan_detail

namespace voxray {

template <class Kernel>
class vulkan_appearance_walker {
    static constexpr vulkan_detail::spirv_modules modules_ = vulkan_detail::find_modules(Kernel::name);
    static_assert(!modules_.appearance.empty(),
                  "this structure has no SPIR-V walk module (voxray_add_appearance_walk, CMake)");

public:
    static constexpr const char* backend = "vulkan";

    // `blob` is the structure's words, `table` the appearance of its voxels; both are
    // uploaded here and may die after the call.
    vulkan_appearance_walker(std::span<const std::uint32_t> blob, const appearance::appearance_table& table,
                             const vulkan_options& options = {})
        : ctx_(vulkan_detail::shared_context(options)),
          commands_(std::make_unique<vulkan_detail::command_stream>(*ctx_)),
          pipeline_(std::make_unique<vulkan_detail::compute_pipeline>(*ctx_, modules_.appearance,
                                                                      std::uint32_t(sizeof(vulkan_detail::appearance_push)))),
          mapped_(!options.force_staging) {
        VkDeviceSize most = std::min(ctx_->max_buffer(), ctx_->max_allocation());
        slice_ = std::min<std::size_t>(slice_, std::max<VkDeviceSize>(most / sizeof(appearance_pixel), 1));
        appearance::walk_words words(table);
        kind_ = words.kind, shadows_ = words.shadows;
        blob_ = upload(std::as_bytes(blob), "structure blob");
        index_ = upload(std::as_bytes(std::span(words.index)), "ordinal index");
        records_ = upload(std::as_bytes(std::span(words.records)), "appearance records");
        faces_ = upload(std::as_bytes(std::span(words.faces)), "appearance face pool");
    }
    vulkan_appearance_walker(vulkan_appearance_walker&&) = delete;  // buffers die before the context (member order)

    std::string device_name() const { return ctx_->name(); }

    // Rays' directions must be unit vectors (records are evaluated for them).
    std::vector<appearance_pixel> walk(std::span<const ray> rays, const appearance_light& light) {
        const std::uint32_t shadows_at = shadows_.at_for(light);
        std::vector<appearance_pixel> out(rays.size());
        for (std::size_t first = 0; first < rays.size(); first += slice_) {
            std::size_t n = std::min(slice_, rays.size() - first);
            walk_slice(rays.subspan(first, n), std::span(out).subspan(first, n), light, shadows_at);
        }
        appearance::check_walked(out);
        return out;
    }

private:
    // One submission: rays in, every dispatch, pixels out, through grow-only buffers.
    void walk_slice(std::span<const ray> rays, std::span<appearance_pixel> out, const appearance_light& light,
                    std::uint32_t shadows_at) {
        using namespace vulkan_detail;
        // The constructor bounded slice_ by the device's buffer limits.
        io_.reserve_records(*ctx_, rays.size(), slice_, sizeof(ray), sizeof(appearance_pixel), mapped_, "ray buffer",
                            "pixel buffer");
        VkCommandBuffer cmd = commands_->begin();
        io_.write_inputs(cmd, rays.data(), rays.size_bytes());
        std::size_t per = std::size_t(ctx_->properties().limits.maxComputeWorkGroupCount[0]) * group_size;
        for (std::size_t first = 0; first < rays.size(); first += per) {
            std::size_t n = std::min(per, rays.size() - first);
            appearance_push pc{blob_.address(), index_.address(), records_.address(), faces_.address(),
                               io_.input_address() + first * sizeof(ray),
                               io_.output_address() + first * sizeof(appearance_pixel),
                               {light.to_light.x, light.to_light.y, light.to_light.z}, light.ambient, light.cutoff,
                               light.max_visits, kind_, std::uint32_t(n), shadows_at};
            pipeline_->bind(cmd, pc);
            vkCmdDispatch(cmd, std::uint32_t((n + group_size - 1) / group_size), 1, 1);
        }
        io_.record_read_back(cmd, out.size_bytes());
        commands_->submit_and_wait();
        io_.read_outputs(out.data(), out.size_bytes());
    }

    void check_size(VkDeviceSize bytes, const char* what) const {
        VkDeviceSize most = std::min(ctx_->max_buffer(), ctx_->max_allocation());
        if (bytes > most)
            fail("vulkan appearance walk: the ", what, " needs ", bytes, " bytes, above the ", most,
                 " bytes one buffer may hold on ", ctx_->name(), " (maxBufferSize, maxMemoryAllocationSize)");
    }

    // A storage buffer holding `bytes` (at least 4 bytes), written directly where the
    // memory is mapped, else through a staging copy.
    vulkan_detail::buffer upload(std::span<const std::byte> bytes, const char* what) {
        using namespace vulkan_detail;
        VkDeviceSize size = std::max<VkDeviceSize>(bytes.size(), 4);
        check_size(size, what);
        buffer b(*ctx_, size, buffer_role::storage_upload, mapped_, what);
        if (bytes.empty()) return b;
        if (b.mapped()) {
            std::memcpy(b.mapped(), bytes.data(), bytes.size());
            return b;  // host writes before vkQueueSubmit are visible to the device
        }
        buffer staging(*ctx_, size, buffer_role::staging_upload, true, what);
        std::memcpy(staging.mapped(), bytes.data(), bytes.size());
        VkCommandBuffer cmd = commands_->begin();
        VkBufferCopy region{0, 0, bytes.size()};
        vkCmdCopyBuffer(cmd, staging.handle(), b.handle(), 1, &region);
        command_stream::barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
        commands_->submit_and_wait();
        return b;
    }

    // Declaration order is destruction order reversed: the context goes last.
    std::shared_ptr<vulkan_detail::context> ctx_;
    std::unique_ptr<vulkan_detail::command_stream> commands_;
    std::unique_ptr<vulkan_detail::compute_pipeline> pipeline_;
    bool mapped_;
    std::uint32_t kind_ = 0;
    appearance::walk_shadows shadows_;
    vulkan_detail::buffer blob_, index_, records_, faces_;
    vulkan_detail::round_trip_buffers io_;  // rays in, pixels out
    // Rays a submission: bounds the ray and pixel buffers (128 MiB of pixels at most, less
    // where the device's buffers are smaller).
    std::size_t slice_ = vulkan_detail::max_slice_rays;
};

}  // namespace voxray
