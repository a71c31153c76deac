// The images a headless raster frame draws into and the render pass over them: colour
// (RGBA8), identity (four 32-bit integers a pixel: voxel x, y, z and face) and depth (32-bit
// float, reversed: 1 near, 0 far), plus the host buffer both colour images are copied to.
// Made for one size; chunk_rasterizer makes new ones when the size changes.
#pragma once
#include <algorithm>
#include <cstdint>

#include <vulkan/vulkan.h>

#include "voxray/core/error.hpp"
#include "voxray/vulkan/buffer.hpp"
#include "voxray/vulkan/check.hpp"
#include "voxray/vulkan/device.hpp"

namespace voxray::vulkan_detail {

inline constexpr VkFormat raster_colour_format = VK_FORMAT_R8G8B8A8_UNORM;
inline constexpr VkFormat raster_identity_format = VK_FORMAT_R32G32B32A32_SINT;
inline constexpr VkFormat raster_depth_format = VK_FORMAT_D32_SFLOAT;
inline constexpr std::uint32_t raster_colour_bytes = 4, raster_identity_bytes = 16;

// One image with its own memory and a view of it.
class raster_image {
public:
    raster_image(const context& ctx, std::uint32_t width, std::uint32_t height, VkFormat format,
                 VkImageUsageFlags usage, VkImageAspectFlags aspect)
        : device_(ctx.device()) {
        try {
            auto info = vk_struct<VkImageCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO);
            info.imageType = VK_IMAGE_TYPE_2D;
            info.format = format;
            info.extent = {width, height, 1};
            info.mipLevels = 1;
            info.arrayLayers = 1;
            info.samples = VK_SAMPLE_COUNT_1_BIT;
            info.tiling = VK_IMAGE_TILING_OPTIMAL;
            info.usage = usage;
            info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
            vk_check(vkCreateImage(device_, &info, nullptr, &image_), "vkCreateImage");
            VkMemoryRequirements req;
            vkGetImageMemoryRequirements(device_, image_, &req);
            auto type = find_memory_type(ctx.memory(), req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
            if (!type) type = find_memory_type(ctx.memory(), req.memoryTypeBits, 0);
            if (!type) fail("vulkan: no memory type suits a ", width, " x ", height, " raster image on ", ctx.name());
            auto alloc = vk_struct<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO);
            alloc.allocationSize = req.size;
            alloc.memoryTypeIndex = *type;
            vk_check(vkAllocateMemory(device_, &alloc, nullptr, &memory_), "vkAllocateMemory (raster image)");
            vk_check(vkBindImageMemory(device_, image_, memory_, 0), "vkBindImageMemory");
            auto view = vk_struct<VkImageViewCreateInfo>(VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO);
            view.image = image_;
            view.viewType = VK_IMAGE_VIEW_TYPE_2D;
            view.format = format;
            view.subresourceRange = {aspect, 0, 1, 0, 1};
            vk_check(vkCreateImageView(device_, &view, nullptr, &view_), "vkCreateImageView");
        } catch (...) {
            destroy();
            throw;
        }
    }
    ~raster_image() { destroy(); }
    raster_image(const raster_image&) = delete;
    raster_image& operator=(const raster_image&) = delete;

    VkImage handle() const { return image_; }
    VkImageView view() const { return view_; }

private:
    void destroy() {
        if (view_) vkDestroyImageView(device_, view_, nullptr);
        if (image_) vkDestroyImage(device_, image_, nullptr);
        if (memory_) vkFreeMemory(device_, memory_, nullptr);
        view_ = VK_NULL_HANDLE, image_ = VK_NULL_HANDLE, memory_ = VK_NULL_HANDLE;
    }

    VkDevice device_;
    VkImage image_ = VK_NULL_HANDLE;
    VkDeviceMemory memory_ = VK_NULL_HANDLE;
    VkImageView view_ = VK_NULL_HANDLE;
};

// Fails, naming the size and the device's limit, unless a frame of width x height fits.
inline void check_raster_size(const context& ctx, std::uint32_t width, std::uint32_t height) {
    std::uint32_t most = ctx.properties().limits.maxFramebufferWidth;
    most = std::min(most, ctx.properties().limits.maxFramebufferHeight);
    most = std::min(most, ctx.properties().limits.maxImageDimension2D);
    if (width == 0 || height == 0 || width > most || height > most)
        fail("vulkan: a raster frame of ", width, " x ", height, " pixels: each side must lie in 1..", most,
             " (the framebuffer and image limits of ", ctx.name(), ")");
}

// The render pass: it clears all three, and leaves colour and identity ready to copy.
inline VkRenderPass create_raster_pass(VkDevice device) {
    VkAttachmentDescription attachments[3]{};
    VkFormat formats[3] = {raster_colour_format, raster_identity_format, raster_depth_format};
    for (int i = 0; i < 3; ++i) {
        attachments[i].format = formats[i];
        attachments[i].samples = VK_SAMPLE_COUNT_1_BIT;
        attachments[i].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
        attachments[i].storeOp = i < 2 ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
        attachments[i].stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
        attachments[i].stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
        attachments[i].initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
        attachments[i].finalLayout =
            i < 2 ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL;
    }
    VkAttachmentReference colours[2] = {{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL},
                                        {1, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL}};
    VkAttachmentReference depth{2, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 2;
    subpass.pColorAttachments = colours;
    subpass.pDepthStencilAttachment = &depth;
    // The copies after the pass wait for its colour writes.
    VkSubpassDependency after{};
    after.srcSubpass = 0;
    after.dstSubpass = VK_SUBPASS_EXTERNAL;
    after.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
    after.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    after.dstStageMask = VK_PIPELINE_STAGE_TRANSFER_BIT;
    after.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    auto info = vk_struct<VkRenderPassCreateInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO);
    info.attachmentCount = 3;
    info.pAttachments = attachments;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = 1;
    info.pDependencies = &after;
    VkRenderPass pass = VK_NULL_HANDLE;
    vk_check(vkCreateRenderPass(device, &info, nullptr, &pass), "vkCreateRenderPass");
    return pass;
}

class raster_targets {
public:
    raster_targets(const context& ctx, VkRenderPass pass, std::uint32_t width, std::uint32_t height)
        : device_(ctx.device()), width_(width), height_(height),
          colour_(ctx, width, height, raster_colour_format,
                  VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT),
          identity_(ctx, width, height, raster_identity_format,
                    VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_IMAGE_ASPECT_COLOR_BIT),
          depth_(ctx, width, height, raster_depth_format, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                 VK_IMAGE_ASPECT_DEPTH_BIT),
          readback_(ctx, VkDeviceSize(width) * height * (raster_colour_bytes + raster_identity_bytes),
                    buffer_role::staging_readback, false, "raster frame read-back") {
        VkImageView views[3] = {colour_.view(), identity_.view(), depth_.view()};
        auto info = vk_struct<VkFramebufferCreateInfo>(VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO);
        info.renderPass = pass;
        info.attachmentCount = 3;
        info.pAttachments = views;
        info.width = width;
        info.height = height;
        info.layers = 1;
        vk_check(vkCreateFramebuffer(device_, &info, nullptr, &framebuffer_), "vkCreateFramebuffer");
    }
    ~raster_targets() {
        if (framebuffer_) vkDestroyFramebuffer(device_, framebuffer_, nullptr);
    }
    raster_targets(const raster_targets&) = delete;
    raster_targets& operator=(const raster_targets&) = delete;

    std::uint32_t width() const { return width_; }
    std::uint32_t height() const { return height_; }
    VkFramebuffer framebuffer() const { return framebuffer_; }
    VkDeviceSize identity_offset() const { return VkDeviceSize(width_) * height_ * raster_colour_bytes; }
    const buffer& readback() const { return readback_; }

    // After the render pass: colour, then identity, into the read-back buffer, then made
    // visible to the host.
    void record_copies(VkCommandBuffer cmd) const {
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = {width_, height_, 1};
        vkCmdCopyImageToBuffer(cmd, colour_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.handle(), 1,
                               &region);
        region.bufferOffset = identity_offset();
        vkCmdCopyImageToBuffer(cmd, identity_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.handle(), 1,
                               &region);
        auto b = vk_struct<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
        b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
        b.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
        vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &b, 0, nullptr, 0,
                             nullptr);
    }

private:
    VkDevice device_;
    std::uint32_t width_, height_;
    raster_image colour_, identity_, depth_;
    buffer readback_;
    VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
};

}  // namespace voxray::vulkan_detail
