// What the raster paths (chunk_raster.hpp, triangle_raster.hpp) share: the view and frame
// types, and the canvas that draws one frame headless on the Vulkan device the tracers
// use: the render pass, its images (raster_targets.hpp), the camera's push constants, the
// submission, GPU timestamps and the read-back of colour and identity.
#pragma once
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <vector>

#include <glm/vec3.hpp>
#include <vulkan/vulkan.h>

#include "voxray/core/error.hpp"
#include "voxray/meshing/layout.h"
#include "voxray/meshing/raster_pixel.hpp"
#include "voxray/rays/camera.hpp"
#include "voxray/vulkan/buffer.hpp"
#include "voxray/vulkan/commands.hpp"
#include "voxray/vulkan/device.hpp"
#include "voxray/vulkan/kernel_timer.hpp"
#include "voxray/vulkan/options.hpp"
#include "voxray/vulkan/raster_pipeline.hpp"
#include "voxray/vulkan/raster_targets.hpp"

namespace voxray {

struct raster_view {
    camera cam;
    int width = 0, height = 0;
    // meshing/pop.h's t = log2(distance) - lod_bias: larger is finer; 64 draws level 0 everywhere.
    float lod_bias = 0.0f;
    int fixed_level = -1;                // 0..6: every chunk at this level, unmorphed; -1: by distance
    glm::vec3 to_sun{0.0f, 1.0f, 0.0f};  // unit length; lights like voxray::shade
    bool cull_faces = true;              // skip a chunk's face directions that face away
};

struct raster_frame {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;    // rows top to bottom; alpha 0 where nothing was drawn
    std::vector<raster_pixel> pixels;  // the identity attachment, same order
    std::uint64_t triangles = 0;       // triangles drawn
    std::uint64_t quads = 0;           // chunk quads drawn (2 triangles each)
    std::uint32_t draws = 0;           // ranges drawn: (chunk, face direction) for chunk meshes
    std::uint32_t culled = 0;          // ranges skipped: facing away or behind the eye
    double gpu_ms = NAN;               // the render pass on the device (GPU timestamps)
    double ms = 0;                     // recording, submission and read-back, on the host
};

namespace vulkan_detail {

class raster_canvas {
public:
    explicit raster_canvas(const vulkan_options& options)
        : ctx_(shared_context(options)), commands_(*ctx_), timer_(*ctx_) {
        if (!ctx_->graphics())
            fail("vulkan: the queue voxray uses on ", ctx_->name(),
                 " cannot draw (its family has no VK_QUEUE_GRAPHICS_BIT); the raster path needs one");
        pass_ = create_raster_pass(ctx_->device());
    }
    ~raster_canvas() {
        targets_.reset();
        vkDestroyRenderPass(ctx_->device(), pass_, nullptr);
    }
    raster_canvas(const raster_canvas&) = delete;
    raster_canvas& operator=(const raster_canvas&) = delete;

    const context& ctx() const { return *ctx_; }
    VkRenderPass pass() const { return pass_; }

    // A shader-readable buffer holding `bytes` of `data` (at least 16 bytes: none is empty),
    // written directly where the device memory maps, else copied through staging memory.
    buffer filled(const void* data, std::size_t bytes, const char* what) {
        VkDeviceSize size = std::max<VkDeviceSize>(bytes, 16);
        buffer b(*ctx_, size, buffer_role::storage_upload, true, what);
        if (bytes == 0) return b;
        if (b.mapped()) {
            std::memcpy(b.mapped(), data, bytes);
            return b;
        }
        buffer staging(*ctx_, size, buffer_role::staging_upload, false, what);
        std::memcpy(staging.mapped(), data, bytes);
        VkCommandBuffer cmd = commands_.begin();
        VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, staging.handle(), b.handle(), 1, &region);
        commands_.submit_and_wait();
        return b;
    }

    // The camera's part of the push constants: a clip-space matrix over eye-relative
    // positions, x and y through the pixel centres exactly as camera_frame::pixel aims its
    // rays (Vulkan's framebuffer y points down), and reversed depth near / distance along
    // the view, with no far plane.
    static raster_push camera_push(const raster_view& view) {
        constexpr float near = 0.05f;
        camera_frame b(view.cam, view.width, view.height);
        raster_push p{};
        for (int c = 0; c < 3; ++c) {
            p.view_projection[4 * c + 0] = b.right[c] / b.half_w;
            p.view_projection[4 * c + 1] = -b.up[c] / b.half_h;
            p.view_projection[4 * c + 2] = 0.0f;
            p.view_projection[4 * c + 3] = b.forward[c];
        }
        p.view_projection[14] = near;  // column 3, row 2
        p.eye_and_bias[0] = view.cam.position.x, p.eye_and_bias[1] = view.cam.position.y;
        p.eye_and_bias[2] = view.cam.position.z, p.eye_and_bias[3] = view.lod_bias;
        p.sun[0] = view.to_sun.x, p.sun[1] = view.to_sun.y, p.sun[2] = view.to_sun.z;
        p.fixed_level = view.fixed_level < 0 ? raster_by_distance : std::uint32_t(view.fixed_level);
        return p;
    }

    // One frame into `frame` (its counts are the caller's): `prepare(cmd)` records what must
    // come before the render pass (copies), `draw(cmd)` the draws, with the viewport set.
    template <class Prepare, class Draw>
    void render(const raster_view& view, raster_frame& frame, Prepare&& prepare, Draw&& draw) {
        auto start = std::chrono::steady_clock::now();
        if (view.width <= 0 || view.height <= 0)
            fail("vulkan: a raster frame of ", view.width, " x ", view.height, " pixels");
        if (view.fixed_level >= VX_MESH_LEVELS)
            fail("vulkan: raster_view::fixed_level ", view.fixed_level, ": levels of detail are 0..",
                 VX_MESH_LEVELS - 1, " (or -1: by distance)");
        auto width = std::uint32_t(view.width), height = std::uint32_t(view.height);
        check_raster_size(*ctx_, width, height);
        if (!targets_ || targets_->width() != width || targets_->height() != height) {
            targets_.reset();
            targets_ = std::make_unique<raster_targets>(*ctx_, pass_, width, height);
        }
        frame.width = view.width, frame.height = view.height;
        VkCommandBuffer cmd = commands_.begin();
        prepare(cmd);
        timer_.start(cmd);
        VkClearValue clears[3]{};
        clears[1].color.int32[3] = std::int32_t(VX_FACE_NONE);
        clears[2].depthStencil = {0.0f, 0};  // reversed depth: 0 is infinitely far
        auto begin = vk_struct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
        begin.renderPass = pass_;
        begin.framebuffer = targets_->framebuffer();
        begin.renderArea.extent = {width, height};
        begin.clearValueCount = 3;
        begin.pClearValues = clears;
        vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
        VkViewport viewport{0.0f, 0.0f, float(width), float(height), 0.0f, 1.0f};
        VkRect2D scissor{{0, 0}, {width, height}};
        vkCmdSetViewport(cmd, 0, 1, &viewport);
        vkCmdSetScissor(cmd, 0, 1, &scissor);
        draw(cmd);
        vkCmdEndRenderPass(cmd);
        timer_.stop(cmd);
        targets_->record_copies(cmd);
        commands_.submit_and_wait();
        frame.gpu_ms = timer_.seconds() * 1e3;
        read_back(frame);
        frame.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }

private:
    void read_back(raster_frame& frame) const {
        std::size_t n = std::size_t(frame.width) * std::size_t(frame.height);
        const auto* bytes = static_cast<const std::uint8_t*>(targets_->readback().mapped());
        frame.rgba.assign(bytes, bytes + n * raster_colour_bytes);
        frame.pixels.resize(n);
        std::vector<std::int32_t> ids(4 * n);
        std::memcpy(ids.data(), bytes + targets_->identity_offset(), n * raster_identity_bytes);
        for (std::size_t i = 0; i < n; ++i)
            frame.pixels[i] = {{ids[4 * i], ids[4 * i + 1], ids[4 * i + 2]}, std::uint32_t(ids[4 * i + 3])};
    }

    std::shared_ptr<context> ctx_;
    command_stream commands_;
    kernel_timer timer_;
    VkRenderPass pass_ = VK_NULL_HANDLE;
    std::unique_ptr<raster_targets> targets_;
};

}  // namespace vulkan_detail
}  // namespace voxray
