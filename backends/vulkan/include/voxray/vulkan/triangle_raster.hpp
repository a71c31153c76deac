// Drawing indexed triangle meshes headless with the camera, light and images of the chunk
// raster path (raster_canvas.hpp), so that other tools' meshes can be compared with chunk
// meshes pixel by pixel: `voxray mesh-bench` draws meshoptimizer's simplifications of the
// level-0 chunk meshes beside the POP levels.
//
//   voxray::triangle_rasterizer raster;
//   raster.upload(positions, indices, 0xFFB3B3B3u);  // xyz per vertex, 3 indices a triangle, RGBA8
//   voxray::raster_frame f = raster.draw(view);       // f.rgba; f.pixels say VX_FACE_INSIDE where drawn
//
// Each triangle is lit by its own plane; its winding is ignored for lighting but decides
// culling (counter-clockwise seen from outside, like the chunk quads).
#pragma once
#include <cstdint>
#include <span>
#include <string>

#include <vulkan/vulkan.h>

#include "voxray/core/error.hpp"
#include "voxray/generated/spirv_triangle_raster_frag.hpp"
#include "voxray/generated/spirv_triangle_raster_vert.hpp"
#include "voxray/vulkan/buffer.hpp"
#include "voxray/vulkan/options.hpp"
#include "voxray/vulkan/raster_canvas.hpp"
#include "voxray/vulkan/raster_pipeline.hpp"

namespace voxray {

class triangle_rasterizer {
public:
    explicit triangle_rasterizer(const vulkan_options& options = {})
        : canvas_(options),
          pipeline_(canvas_.ctx().device(), canvas_.pass(), voxray_spirv_triangle_raster_vert,
                    voxray_spirv_triangle_raster_frag) {}

    std::string device_name() const { return canvas_.ctx().name(); }

    // The mesh to draw (replacing any before): 3 floats a vertex, 3 indices a triangle,
    // every index below the vertex count; one RGBA8 colour (r in the low byte).
    void upload(std::span<const float> positions, std::span<const std::uint32_t> indices, std::uint32_t colour) {
        if (positions.size() % 3 != 0)
            fail("triangle_rasterizer::upload: ", positions.size(), " floats are not whole xyz vertices");
        if (indices.size() % 3 != 0)
            fail("triangle_rasterizer::upload: ", indices.size(), " indices are not whole triangles");
        std::size_t vertices = positions.size() / 3;
        for (std::size_t i = 0; i < indices.size(); ++i)
            if (indices[i] >= vertices)
                fail("triangle_rasterizer::upload: index ", i, " is ", indices[i], ", beyond the ", vertices,
                     " vertices");
        positions_ = canvas_.filled(positions.data(), positions.size_bytes(), "triangle positions");
        indices_ = canvas_.filled(indices.data(), indices.size_bytes(), "triangle indices");
        colour_ = canvas_.filled(&colour, sizeof colour, "triangle colour");
        index_count_ = std::uint32_t(indices.size());
        uploaded_ = true;
    }

    raster_frame draw(const raster_view& view) {
        if (!uploaded_) fail("triangle_rasterizer::draw: no mesh uploaded (call upload first)");
        raster_frame frame;
        vulkan_detail::raster_push push = vulkan_detail::raster_canvas::camera_push(view);
        push.data[0] = positions_.address(), push.data[1] = indices_.address(), push.data[2] = colour_.address();
        push.colour_count = 1;
        frame.triangles = index_count_ / 3;
        frame.draws = index_count_ ? 1 : 0;
        canvas_.render(
            view, frame, [](VkCommandBuffer) {},
            [&](VkCommandBuffer cmd) {
                pipeline_.bind(cmd, push);
                if (index_count_) vkCmdDraw(cmd, index_count_, 1, 0, 0);
            });
        return frame;
    }

private:
    vulkan_detail::raster_canvas canvas_;
    vulkan_detail::raster_pipeline pipeline_;
    vulkan_detail::buffer positions_, indices_, colour_;
    std::uint32_t index_count_ = 0;
    bool uploaded_ = false;
};

}  // namespace voxray
