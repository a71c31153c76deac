// The mesher kernel (meshing/kernel.h) on a Vulkan device: chunks in, the CPU mesher's
// quads and POP order out (meshing/kernel_mesher.hpp). The module is mesher_passes (one
// compute shader, shaders/pass_entry.glsl); its passes run through the frame-pass runner
// (vulkan/passes.hpp), the chunks are its blob and the meshes its frame, which stays on the
// device for a renderer that pulls quads from it (frame_address()).
//
//   voxray::vulkan_chunk_mesher mesher({.ambient_occlusion = true});
//   std::vector<voxray::meshing::chunk_mesh> meshes = mesher.mesh(chunks);
#pragma once
#include <cstdint>
#include <cstring>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <vulkan/vulkan.h>

#if !defined(VOXRAY_LINKED_VULKAN)
#error "voxray/vulkan/chunk_mesher.hpp needs voxray::vulkan: link it"
#endif
#include "voxray/generated/spirv_mesher_passes.hpp"
#include "voxray/meshing/kernel_mesher.hpp"
#include "voxray/vulkan/buffer.hpp"
#include "voxray/vulkan/commands.hpp"
#include "voxray/vulkan/device.hpp"
#include "voxray/vulkan/options.hpp"
#include "voxray/vulkan/passes.hpp"

namespace voxray::vulkan_detail {

class mesher_device {
public:
    static constexpr const char* backend = "vulkan";

    explicit mesher_device(const vulkan_options& options = {})
        : ctx_(shared_context(options)), commands_(std::make_unique<command_stream>(*ctx_)) {}
    mesher_device(mesher_device&&) = delete;  // the buffers die before the context (member order)

    std::string device_name() const { return ctx_->name(); }
    void upload(std::span<const std::uint32_t> words) {
        VkDeviceSize bytes = std::max<VkDeviceSize>(words.size_bytes(), 4);
        if (blob_.size() < bytes) {
            blob_ = buffer();  // free the old one first: both may not fit at once
            blob_ = buffer(*ctx_, bytes, buffer_role::storage_upload, true, "mesher chunks");
        }
        if (blob_.mapped()) {
            std::memcpy(blob_.mapped(), words.data(), words.size_bytes());
            return;  // host writes before vkQueueSubmit are visible to the device
        }
        buffer staging(*ctx_, bytes, buffer_role::staging_upload, true, "mesher chunks staging buffer");
        std::memcpy(staging.mapped(), words.data(), words.size_bytes());
        VkCommandBuffer cmd = commands_->begin();
        VkBufferCopy region{0, 0, words.size_bytes()};
        vkCmdCopyBuffer(cmd, staging.handle(), blob_.handle(), 1, &region);
        command_stream::barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                                VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_READ_BIT);
        commands_->submit_and_wait();
    }
    void frame_reserve(std::size_t words) { passes_.reserve(*ctx_, words); }
    void frame_write(std::size_t at, std::span<const std::uint32_t> words) {
        passes_.write(*ctx_, *commands_, at, words);
    }
    void frame_read(std::size_t at, std::span<std::uint32_t> words) { passes_.read(*ctx_, *commands_, at, words); }
    void run_pass(std::uint32_t pass, std::uint64_t items) {
        if (items > 0) passes_.run(*ctx_, *commands_, voxray_spirv_mesher_passes, blob_.address(), pass, items);
    }
    // The frame's device address: chunk i's quads start at word kernel_mesher::quads_word(i).
    VkDeviceAddress frame_address() const { return passes_.address(); }

private:
    // Declaration order is destruction order reversed: the context goes last.
    std::shared_ptr<context> ctx_;
    std::unique_ptr<command_stream> commands_;
    buffer blob_;
    pass_runner passes_{false};
};

}  // namespace voxray::vulkan_detail

namespace voxray {
using vulkan_chunk_mesher = meshing::kernel_mesher<vulkan_detail::mesher_device>;
}  // namespace voxray
