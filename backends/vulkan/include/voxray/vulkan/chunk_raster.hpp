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
#include <cstdint>
#include <cstring>
#include <limits>
#include <span>
#include <string>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <vulkan/vulkan.h>

#include "voxray/core/error.hpp"
#include "voxray/generated/spirv_chunk_raster_frag.hpp"
#include "voxray/generated/spirv_chunk_raster_vert.hpp"
#include "voxray/meshing/chunk_mesh.hpp"
#include "voxray/meshing/pop.hpp"
#include "voxray/rays/camera.hpp"
#include "voxray/vulkan/buffer.hpp"
#include "voxray/vulkan/commands.hpp"
#include "voxray/vulkan/options.hpp"
#include "voxray/vulkan/raster_canvas.hpp"
#include "voxray/vulkan/raster_pipeline.hpp"

namespace voxray {

// Where a chunk mesh stands: world position = world_origin + (position in cells) << cell_bits.
// The default places a mesh of voxels as it is; a chunk of an open world's LOD n has cells
// of 2^n voxels (meshing/world_chunk_source.hpp).
struct chunk_placement {
    glm::ivec3 world_origin{0};
    int cell_bits = 0;
};

class chunk_rasterizer {
public:
    explicit chunk_rasterizer(const vulkan_options& options = {})
        : canvas_(options),
          pipeline_(canvas_.ctx().device(), canvas_.pass(), voxray_spirv_chunk_raster_vert,
                    voxray_spirv_chunk_raster_frag) {}

    std::string device_name() const { return canvas_.ctx().name(); }

    // The chunks to draw (replacing any before) and the colour of each material, RGBA8
    // (r in the low byte); a material past the end draws magenta. `placements`: one per
    // mesh, or none for meshes of voxels in place.
    void upload(std::span<const meshing::chunk_mesh> meshes, std::span<const std::uint32_t> colours,
                std::span<const chunk_placement> placements = {}) {
        if (!placements.empty() && placements.size() != meshes.size())
            fail("chunk_rasterizer::upload: ", placements.size(), " placements for ", meshes.size(), " meshes");
        std::vector<std::uint32_t> words;
        std::vector<std::array<std::int32_t, 8>> origins;  // the shader's two ivec4s a chunk
        chunks_.clear();
        for (std::size_t i = 0; i < meshes.size(); ++i) {
            const auto& m = meshes[i];
            chunk_placement at = placements.empty() ? chunk_placement{} : placements[i];
            if (at.cell_bits < 0 || at.cell_bits > 16)
                fail("chunk_rasterizer::upload: placement ", i, " has cells of 2^", at.cell_bits,
                     " voxels (0..16 allowed)");
            chunks_.push_back({m.origin, at, std::uint64_t(words.size() / VX_MESH_QUAD_WORDS), m.table});
            origins.push_back({m.origin.x, m.origin.y, m.origin.z, at.cell_bits, at.world_origin.x, at.world_origin.y,
                               at.world_origin.z, 0});
            words.insert(words.end(), m.words.begin(), m.words.end());
        }
        std::uint64_t quads = words.size() / VX_MESH_QUAD_WORDS;
        constexpr std::uint64_t most = std::numeric_limits<std::uint32_t>::max() / 6;
        if (quads > most)
            fail("vulkan: ", quads, " quads are more than one raster upload draws (at most ", most,
                 ": vertex indices are 32-bit, 6 a quad)");
        quads_ = canvas_.filled(words.data(), words.size() * sizeof(std::uint32_t), "chunk quads");
        placements_ = canvas_.filled(origins.data(), origins.size() * sizeof(origins[0]), "chunk placements");
        colours_ = canvas_.filled(colours.data(), colours.size_bytes(), "material colours");
        colour_count_ = std::uint32_t(colours.size());
        const auto& ctx = canvas_.ctx();
        VkDeviceSize commands = VkDeviceSize(std::max<std::size_t>(chunks_.size(), 1)) * VX_MESH_FACES *
                                sizeof(VkDrawIndirectCommand);
        indirect_ = vulkan_detail::buffer(ctx, commands, vulkan_detail::buffer_role::storage_upload, true,
                                          "raster draw commands");
        indirect_staging_ = {};
        if (!indirect_.mapped())
            indirect_staging_ = vulkan_detail::buffer(ctx, commands, vulkan_detail::buffer_role::staging_upload, false,
                                                      "raster draw commands (staging)");
    }

    raster_frame draw(const raster_view& view) {
        if (!quads_.handle()) fail("chunk_rasterizer::draw: no chunks uploaded (call upload first)");
        raster_frame frame;
        std::vector<VkDrawIndirectCommand> list = draw_list(view, frame);
        vulkan_detail::raster_push push = vulkan_detail::raster_canvas::camera_push(view);
        push.data[0] = quads_.address(), push.data[1] = placements_.address(), push.data[2] = colours_.address();
        push.colour_count = colour_count_;
        bool indirect = canvas_.ctx().indirect_draws() && !list.empty();
        canvas_.render(
            view, frame, [&](VkCommandBuffer cmd) { if (indirect) write_commands(cmd, list); },
            [&](VkCommandBuffer cmd) {
                pipeline_.bind(cmd, push);
                if (indirect)
                    vkCmdDrawIndirect(cmd, indirect_.handle(), 0, std::uint32_t(list.size()),
                                      sizeof(VkDrawIndirectCommand));
                else
                    for (const auto& c : list) vkCmdDraw(cmd, c.vertexCount, 1, c.firstVertex, c.firstInstance);
            });
        return frame;
    }

private:
    struct chunk_entry {
        glm::ivec3 origin;  // in cells
        chunk_placement at;
        std::uint64_t first_quad;
        std::array<std::uint32_t, VX_MESH_TABLE_ENTRIES> table;
    };

    // One range per (chunk, face direction) left after culling.
    std::vector<VkDrawIndirectCommand> draw_list(const raster_view& view, raster_frame& frame) const {
        std::vector<VkDrawIndirectCommand> list;
        glm::vec3 forward = camera_frame(view.cam, 1, 1).forward;
        for (std::size_t i = 0; i < chunks_.size(); ++i) {
            const chunk_entry& c = chunks_[i];
            // The eye in the chunk's cells, as the vertex shader brings it there.
            float cell = float(1 << c.at.cell_bits);
            glm::vec3 eye = (view.cam.position - glm::vec3(c.at.world_origin)) / cell;
            meshing::pop_view pop{eye, view.lod_bias};
            glm::vec3 lo(c.origin), hi = lo + float(VX_MESH_CHUNK_EDGE);
            // Behind the eye: every corner of the chunk's box on the far side of the eye's plane.
            bool behind = view.cull_faces;
            for (int k = 0; k < 8 && behind; ++k) {
                glm::vec3 corner((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
                behind = glm::dot(corner - eye, forward) < 0.0f;  // cells scale uniformly
            }
            int level = view.fixed_level >= 0 ? view.fixed_level : meshing::chunk_draw_level(c.origin, pop);
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
        frame.triangles = 2 * frame.quads;
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

    vulkan_detail::raster_canvas canvas_;
    vulkan_detail::raster_pipeline pipeline_;
    std::vector<chunk_entry> chunks_;
    vulkan_detail::buffer quads_, placements_, colours_, indirect_, indirect_staging_;
    std::uint32_t colour_count_ = 0;
};

}  // namespace voxray
