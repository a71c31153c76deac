// A graphics pipeline of the raster paths: a vertex and a fragment shader built from
// backends/vulkan/shaders/<program>_*.glsl, no vertex input (the vertex shaders pull what
// they draw by device address), back faces culled, reversed depth (greater is nearer), and
// viewport and scissor set per frame. Push constants only, like the trace pipelines.
#pragma once
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

#include "voxray/vulkan/check.hpp"
#include "voxray/vulkan/device.hpp"

namespace voxray::vulkan_detail {

// raster_push::fixed_level when the level of detail follows the distance.
inline constexpr std::uint32_t raster_by_distance = 0xFFFFFFFFu;

// Must match vx_raster_push in backends/vulkan/shaders/raster_frame.glsl.
struct raster_push {
    float view_projection[16];  // column-major, eye-relative
    float eye_and_bias[4];
    float sun[4];
    std::uint64_t data[3];  // device addresses: what the program draws, then its colours
    std::uint32_t colour_count, fixed_level;
};
static_assert(std::endian::native == std::endian::little, "addresses are passed as (low, high) word pairs");
static_assert(sizeof(raster_push) == 128, "the least maxPushConstantsSize every device offers");
static_assert(offsetof(raster_push, data) == 96 && offsetof(raster_push, colour_count) == 120);

class raster_pipeline {
public:
    raster_pipeline(VkDevice device, VkRenderPass pass, std::span<const std::uint32_t> vertex_spirv,
                    std::span<const std::uint32_t> fragment_spirv)
        : device_(device) {
        try {
            create(pass, vertex_spirv, fragment_spirv);
        } catch (...) {
            destroy();
            throw;
        }
    }
    ~raster_pipeline() { destroy(); }
    raster_pipeline(const raster_pipeline&) = delete;
    raster_pipeline& operator=(const raster_pipeline&) = delete;

    void bind(VkCommandBuffer cmd, const raster_push& push) const {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline_);
        vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof push,
                           &push);
    }

private:
    VkShaderModule module(std::span<const std::uint32_t> spirv) {
        auto info = vk_struct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
        info.codeSize = spirv.size_bytes();
        info.pCode = spirv.data();
        VkShaderModule m = VK_NULL_HANDLE;
        vk_check(vkCreateShaderModule(device_, &info, nullptr, &m), "vkCreateShaderModule");
        return m;
    }

    void create(VkRenderPass pass, std::span<const std::uint32_t> vertex_spirv,
                std::span<const std::uint32_t> fragment_spirv) {
        vertex_ = module(vertex_spirv);
        fragment_ = module(fragment_spirv);
        VkPushConstantRange range{VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(raster_push)};
        auto layout_info = vk_struct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
        layout_info.pushConstantRangeCount = 1;
        layout_info.pPushConstantRanges = &range;
        vk_check(vkCreatePipelineLayout(device_, &layout_info, nullptr, &layout_), "vkCreatePipelineLayout");

        VkPipelineShaderStageCreateInfo stages[2]{};
        VkShaderStageFlagBits kinds[2] = {VK_SHADER_STAGE_VERTEX_BIT, VK_SHADER_STAGE_FRAGMENT_BIT};
        VkShaderModule modules[2] = {vertex_, fragment_};
        for (int i = 0; i < 2; ++i) {
            stages[i].sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
            stages[i].stage = kinds[i];
            stages[i].module = modules[i];
            stages[i].pName = "main";
        }
        auto vertex_input = vk_struct<VkPipelineVertexInputStateCreateInfo>(
            VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO);
        auto assembly = vk_struct<VkPipelineInputAssemblyStateCreateInfo>(
            VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO);
        assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        auto viewport =
            vk_struct<VkPipelineViewportStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO);
        viewport.viewportCount = 1;
        viewport.scissorCount = 1;
        auto raster = vk_struct<VkPipelineRasterizationStateCreateInfo>(
            VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO);
        raster.polygonMode = VK_POLYGON_MODE_FILL;
        raster.cullMode = VK_CULL_MODE_BACK_BIT;
        // The vertex shaders wind every triangle counter-clockwise seen from outside. Vulkan
        // judges the winding as the picture shows it (its area formula carries a minus for
        // the downward framebuffer y), and the picture is not mirrored: still counter-clockwise.
        raster.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
        raster.lineWidth = 1.0f;
        auto multisample = vk_struct<VkPipelineMultisampleStateCreateInfo>(
            VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO);
        multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
        auto depth = vk_struct<VkPipelineDepthStencilStateCreateInfo>(
            VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO);
        depth.depthTestEnable = VK_TRUE;
        depth.depthWriteEnable = VK_TRUE;
        depth.depthCompareOp = VK_COMPARE_OP_GREATER;  // reversed depth: 1 near, 0 at infinity
        VkPipelineColorBlendAttachmentState blend[2]{};
        for (auto& b : blend)
            b.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT |
                               VK_COLOR_COMPONENT_A_BIT;
        auto blending = vk_struct<VkPipelineColorBlendStateCreateInfo>(
            VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO);
        blending.attachmentCount = 2;
        blending.pAttachments = blend;
        VkDynamicState dynamic_states[2] = {VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
        auto dynamic =
            vk_struct<VkPipelineDynamicStateCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO);
        dynamic.dynamicStateCount = 2;
        dynamic.pDynamicStates = dynamic_states;

        auto info = vk_struct<VkGraphicsPipelineCreateInfo>(VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO);
        info.stageCount = 2;
        info.pStages = stages;
        info.pVertexInputState = &vertex_input;
        info.pInputAssemblyState = &assembly;
        info.pViewportState = &viewport;
        info.pRasterizationState = &raster;
        info.pMultisampleState = &multisample;
        info.pDepthStencilState = &depth;
        info.pColorBlendState = &blending;
        info.pDynamicState = &dynamic;
        info.layout = layout_;
        info.renderPass = pass;
        info.subpass = 0;
        vk_check(vkCreateGraphicsPipelines(device_, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline_),
                 "vkCreateGraphicsPipelines");
    }

    void destroy() {
        if (pipeline_) vkDestroyPipeline(device_, pipeline_, nullptr);
        if (layout_) vkDestroyPipelineLayout(device_, layout_, nullptr);
        if (vertex_) vkDestroyShaderModule(device_, vertex_, nullptr);
        if (fragment_) vkDestroyShaderModule(device_, fragment_, nullptr);
        pipeline_ = VK_NULL_HANDLE, layout_ = VK_NULL_HANDLE, vertex_ = VK_NULL_HANDLE, fragment_ = VK_NULL_HANDLE;
    }

    VkDevice device_;
    VkShaderModule vertex_ = VK_NULL_HANDLE, fragment_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace voxray::vulkan_detail
