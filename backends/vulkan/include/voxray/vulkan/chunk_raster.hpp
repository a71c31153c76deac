// Drawing POP chunk meshes (include/voxray/meshing/) with Vulkan's graphics pipeline,
// headless: the reference raster path beside the ray tracer, and the example of how an
// engine draws them.
//
//   voxray::chunk_rasterizer raster;            // on the Vulkan device the tracers choose
//   raster.upload(meshes, colours);             // chunk meshes and an RGBA8 colour per material
//   voxray::raster_frame f = raster.draw({.cam = cam, .width = 1280, .height = 720, .lod_bias = 6});
//   // f.rgba: the picture; f.pixels: the voxel and face drawn at each pixel
//
// A frame: every chunk draws the prefix of its quads for its level of detail
// (meshing::chunk_draw_level), one range per face direction, all of them from one
// vkCmdDrawIndirect (one vkCmdDraw per range where the device lacks multiDrawIndirect). A
// chunk's face directions that face away from the eye are not drawn (per-chunk culling),
// back faces are culled per triangle, and the vertex shader pulls the quads and morphs them
// with meshing/pop.h, so the geometry is the CPU reference's bit for bit.
#pragma once
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <vulkan/vulkan.h>

#include "voxray/core/error.hpp"
#include "voxray/core/ray_hit_layout.h"
#include "voxray/meshing/chunk_mesh.hpp"
#include "voxray/meshing/pop.hpp"
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
    glm::vec3 to_sun{0.0f, 1.0f, 0.0f};  // unit length; lights like voxray::shade
    bool cull_faces = true;              // skip a chunk's face directions that face away
};

struct raster_frame {
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;    // rows top to bottom; alpha 0 where nothing was drawn
    std::vector<raster_pixel> pixels;  // the identity attachment, same order
    std::uint64_t quads = 0;           // quads drawn
    std::uint32_t draws = 0;           // (chunk, face direction) ranges drawn
    std::uint32_t culled = 0;          // ranges skipped: facing away or behind the eye
    double gpu_ms = NAN;               // the render pass on the device (GPU timestamps)
    double ms = 0;                     // recording, submission and read-back, on the host
};

class chunk_rasterizer {
public:
    explicit chunk_rasterizer(const vulkan_options& options = {})
        : ctx_(vulkan_detail::shared_context(options)), commands_(*ctx_), timer_(*ctx_) {
        if (!ctx_->graphics())
            fail("vulkan: the queue voxray uses on ", ctx_->name(),
                 " cannot draw (its family has no VK_QUEUE_GRAPHICS_BIT); the raster path needs one");
        pass_ = vulkan_detail::create_raster_pass(ctx_->device());
        try {
            pipeline_ = std::make_unique<vulkan_detail::raster_pipeline>(ctx_->device(), pass_);
        } catch (...) {
            vkDestroyRenderPass(ctx_->device(), pass_, nullptr);
            throw;
        }
    }
    ~chunk_rasterizer() {
        targets_.reset();
        pipeline_.reset();
        vkDestroyRenderPass(ctx_->device(), pass_, nullptr);
    }
    chunk_rasterizer(const chunk_rasterizer&) = delete;
    chunk_rasterizer& operator=(const chunk_rasterizer&) = delete;

    std::string device_name() const { return ctx_->name(); }

    // The chunks to draw (replacing any before) and the colour of each material, RGBA8
    // (r in the low byte); a material past the end draws magenta.
    void upload(std::span<const meshing::chunk_mesh> meshes, std::span<const std::uint32_t> colours) {
        std::vector<std::uint32_t> words;
        std::vector<std::array<std::int32_t, 4>> origins;
        chunks_.clear();
        for (const auto& m : meshes) {
            chunks_.push_back({m.origin, std::uint64_t(words.size() / VX_MESH_QUAD_WORDS), m.table});
            origins.push_back({m.origin.x, m.origin.y, m.origin.z, 0});
            words.insert(words.end(), m.words.begin(), m.words.end());
        }
        std::uint64_t quads = words.size() / VX_MESH_QUAD_WORDS;
        constexpr std::uint64_t most = std::numeric_limits<std::uint32_t>::max() / 6;
        if (quads > most)
            fail("vulkan: ", quads, " quads are more than one raster upload draws (at most ", most,
                 ": vertex indices are 32-bit, 6 a quad)");
        quads_ = filled(words.data(), words.size() * sizeof(std::uint32_t), "chunk quads");
        origins_ = filled(origins.data(), origins.size() * sizeof(origins[0]), "chunk origins");
        colours_ = filled(colours.data(), colours.size_bytes(), "material colours");
        colour_count_ = std::uint32_t(colours.size());
        VkDeviceSize commands = VkDeviceSize(std::max<std::size_t>(chunks_.size(), 1)) * VX_MESH_FACES *
                                sizeof(VkDrawIndirectCommand);
        indirect_ = vulkan_detail::buffer(*ctx_, commands, vulkan_detail::buffer_role::storage_upload, true,
                                          "raster draw commands");
        indirect_staging_ = {};
        if (!indirect_.mapped())
            indirect_staging_ = vulkan_detail::buffer(*ctx_, commands, vulkan_detail::buffer_role::staging_upload,
                                                      false, "raster draw commands (staging)");
    }

    raster_frame draw(const raster_view& view) {
        auto start = std::chrono::steady_clock::now();
        if (!quads_.handle()) fail("chunk_rasterizer::draw: no chunks uploaded (call upload first)");
        if (view.width <= 0 || view.height <= 0)
            fail("chunk_rasterizer::draw: a frame of ", view.width, " x ", view.height, " pixels");
        vulkan_detail::check_raster_size(*ctx_, std::uint32_t(view.width), std::uint32_t(view.height));
        if (!targets_ || targets_->width() != std::uint32_t(view.width) ||
            targets_->height() != std::uint32_t(view.height)) {
            targets_.reset();
            targets_ = std::make_unique<vulkan_detail::raster_targets>(*ctx_, pass_, std::uint32_t(view.width),
                                                                      std::uint32_t(view.height));
        }
        raster_frame frame;
        frame.width = view.width, frame.height = view.height;
        camera_frame basis(view.cam, view.width, view.height);
        std::vector<VkDrawIndirectCommand> list = draw_list(view, basis, frame);

        VkCommandBuffer cmd = commands_.begin();
        if (!list.empty()) write_commands(cmd, list);
        timer_.start(cmd);
        VkClearValue clears[3]{};
        clears[1].color.int32[3] = std::int32_t(VX_FACE_NONE);
        clears[2].depthStencil = {0.0f, 0};  // reversed depth: 0 is infinitely far
        auto begin = vulkan_detail::vk_struct<VkRenderPassBeginInfo>(VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO);
        begin.renderPass = pass_;
        begin.framebuffer = targets_->framebuffer();
        begin.renderArea.extent = {std::uint32_t(view.width), std::uint32_t(view.height)};
        begin.clearValueCount = 3;
        begin.pClearValues = clears;
        vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
        VkViewport viewport{0.0f, 0.0f, float(view.width), float(view.height), 0.0f, 1.0f};
        VkRect2D scissor{{0, 0}, {std::uint32_t(view.width), std::uint32_t(view.height)}};
        vkCmdSetViewport(cmd, 0, 1, &viewport);
        vkCmdSetScissor(cmd, 0, 1, &scissor);
        pipeline_->bind(cmd, push(view, basis));
        if (ctx_->indirect_draws() && !list.empty())
            vkCmdDrawIndirect(cmd, indirect_.handle(), 0, std::uint32_t(list.size()), sizeof(VkDrawIndirectCommand));
        else
            for (const auto& c : list) vkCmdDraw(cmd, c.vertexCount, 1, c.firstVertex, c.firstInstance);
        vkCmdEndRenderPass(cmd);
        timer_.stop(cmd);
        targets_->record_copies(cmd);
        commands_.submit_and_wait();
        frame.gpu_ms = timer_.seconds() * 1e3;
        read_back(frame);
        frame.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        return frame;
    }

private:
    struct chunk_entry {
        glm::ivec3 origin;
        std::uint64_t first_quad;
        std::array<std::uint32_t, VX_MESH_TABLE_ENTRIES> table;
    };

    vulkan_detail::buffer filled(const void* data, std::size_t bytes, const char* what) {
        VkDeviceSize size = std::max<VkDeviceSize>(bytes, 16);  // no buffer of 0 bytes
        vulkan_detail::buffer b(*ctx_, size, vulkan_detail::buffer_role::storage_upload, true, what);
        if (bytes == 0) return b;
        if (b.mapped()) {
            std::memcpy(b.mapped(), data, bytes);
            return b;
        }
        vulkan_detail::buffer staging(*ctx_, size, vulkan_detail::buffer_role::staging_upload, false, what);
        std::memcpy(staging.mapped(), data, bytes);
        VkCommandBuffer cmd = commands_.begin();
        VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, staging.handle(), b.handle(), 1, &region);
        commands_.submit_and_wait();
        return b;
    }

    // One range per (chunk, face direction) left after culling.
    std::vector<VkDrawIndirectCommand> draw_list(const raster_view& view, const camera_frame& basis,
                                                 raster_frame& frame) const {
        std::vector<VkDrawIndirectCommand> list;
        meshing::pop_view pop{view.cam.position, view.lod_bias};
        glm::vec3 eye = view.cam.position;
        for (std::size_t i = 0; i < chunks_.size(); ++i) {
            const chunk_entry& c = chunks_[i];
            glm::vec3 lo(c.origin), hi = lo + float(VX_MESH_CHUNK_EDGE);
            // Behind the eye: every corner of the chunk's box on the far side of the eye's plane.
            bool behind = view.cull_faces;
            for (int k = 0; k < 8 && behind; ++k) {
                glm::vec3 corner((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
                behind = glm::dot(corner - eye, basis.forward) < 0.0f;
            }
            int level = meshing::chunk_draw_level(c.origin, pop);
            for (int f = 0; f < VX_MESH_FACES; ++f) {
                std::uint32_t begin = f ? c.table[VX_MESH_TABLE_END(f - 1, 0)] : 0u;
                std::uint32_t end = c.table[VX_MESH_TABLE_END(f, level)];
                if (end == begin) continue;
                if (behind || (view.cull_faces && faces_away(c.origin, f, eye))) {
                    ++frame.culled;
                    continue;
                }
                list.push_back({6u * (end - begin), 1u, std::uint32_t(6u * (c.first_quad + begin)), std::uint32_t(i)});
                frame.quads += end - begin;
            }
        }
        frame.draws = std::uint32_t(list.size());
        return list;
    }

    // Whether every face of direction f in the chunk at `origin` faces away from the eye,
    // whatever the morph: morphing rounds coordinates down, never below the chunk's
    // origin, so a positive face's plane stays at or above origin and a negative one's
    // below origin + 64.
    static bool faces_away(glm::ivec3 origin, int f, glm::vec3 eye) {
        int axis = int(VX_MESH_NORMAL_AXIS(unsigned(f)));
        if (VX_MESH_POSITIVE(unsigned(f))) return eye[axis] <= float(origin[axis]);
        return eye[axis] >= float(origin[axis] + VX_MESH_CHUNK_EDGE);
    }

    void write_commands(VkCommandBuffer cmd, const std::vector<VkDrawIndirectCommand>& list) {
        std::size_t bytes = list.size() * sizeof(list[0]);
        if (indirect_.mapped()) {
            std::memcpy(indirect_.mapped(), list.data(), bytes);
            return;
        }
        std::memcpy(indirect_staging_.mapped(), list.data(), bytes);
        VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, indirect_staging_.handle(), indirect_.handle(), 1, &region);
        vulkan_detail::command_stream::barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
                                               VK_PIPELINE_STAGE_DRAW_INDIRECT_BIT,
                                               VK_ACCESS_INDIRECT_COMMAND_READ_BIT);
    }

    // The camera as a clip-space matrix over eye-relative positions: x and y through the
    // pixel centres exactly as camera_frame::pixel aims its rays (Vulkan's framebuffer y
    // points down), and reversed depth near / distance along the view, with no far plane.
    vulkan_detail::raster_push push(const raster_view& view, const camera_frame& b) const {
        constexpr float near = 0.05f;
        vulkan_detail::raster_push p{};
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
        p.quads = quads_.address(), p.origins = origins_.address(), p.colours = colours_.address();
        p.colour_count = colour_count_;
        return p;
    }

    void read_back(raster_frame& frame) const {
        std::size_t n = std::size_t(frame.width) * std::size_t(frame.height);
        const auto* bytes = static_cast<const std::uint8_t*>(targets_->readback().mapped());
        frame.rgba.assign(bytes, bytes + n * vulkan_detail::raster_colour_bytes);
        frame.pixels.resize(n);
        const auto* ids = reinterpret_cast<const std::int32_t*>(bytes + targets_->identity_offset());
        for (std::size_t i = 0; i < n; ++i)
            frame.pixels[i] = {{ids[4 * i], ids[4 * i + 1], ids[4 * i + 2]}, std::uint32_t(ids[4 * i + 3])};
    }

    std::shared_ptr<vulkan_detail::context> ctx_;
    vulkan_detail::command_stream commands_;
    vulkan_detail::kernel_timer timer_;
    VkRenderPass pass_ = VK_NULL_HANDLE;
    std::unique_ptr<vulkan_detail::raster_pipeline> pipeline_;
    std::unique_ptr<vulkan_detail::raster_targets> targets_;
    std::vector<chunk_entry> chunks_;
    vulkan_detail::buffer quads_, origins_, colours_, indirect_, indirect_staging_;
    std::uint32_t colour_count_ = 0;
};

}  // namespace voxray
