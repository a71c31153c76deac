// A compute pipeline's creation (declared in vulkan/pipeline.hpp).
#pragma once
#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

#include "voxray/vulkan/check.hpp"
#include "voxray/vulkan/device.hpp"
#include "voxray/vulkan/pipeline.hpp"

namespace voxray::vulkan_detail {

VOXRAY_HOST_INLINE compute_pipeline::compute_pipeline(const context& ctx, std::span<const std::uint32_t> spirv,
                                                      std::uint32_t push_bytes)
    : device_(ctx.device()), push_bytes_(push_bytes) {
    try {
        create(spirv, nullptr);
    } catch (...) {
        destroy();
        throw;
    }
}

VOXRAY_HOST_INLINE compute_pipeline::compute_pipeline(const context& ctx, std::span<const std::uint32_t> spirv,
                                                      trace_mode mode, std::uint32_t invocations)
    : device_(ctx.device()), push_bytes_(sizeof(push_constants)) {
    std::uint32_t values[2] = {mode.value, invocations};
    VkSpecializationMapEntry entries[2] = {{trace_mode_constant_id, 0, sizeof(std::uint32_t)},
                                           {trace_group_size_id, sizeof(std::uint32_t), sizeof(std::uint32_t)}};
    VkSpecializationInfo constants{2, entries, sizeof values, values};
    try {
        create(spirv, &constants);
    } catch (...) {
        destroy();
        throw;
    }
}

VOXRAY_HOST_INLINE void compute_pipeline::create(std::span<const std::uint32_t> spirv,
                                                 const VkSpecializationInfo* constants) {
    auto module_info = vk_struct<VkShaderModuleCreateInfo>(VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO);
    module_info.codeSize = spirv.size_bytes();
    module_info.pCode = spirv.data();
    vk_check(vkCreateShaderModule(device_, &module_info, nullptr, &module_), "vkCreateShaderModule");

    // At most 32 bytes: within the 128 bytes every device must offer.
    VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, push_bytes_};
    auto layout_info = vk_struct<VkPipelineLayoutCreateInfo>(VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO);
    layout_info.pushConstantRangeCount = 1;
    layout_info.pPushConstantRanges = &range;
    vk_check(vkCreatePipelineLayout(device_, &layout_info, nullptr, &layout_), "vkCreatePipelineLayout");

    auto info = vk_struct<VkComputePipelineCreateInfo>(VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO);
    info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
    info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
    info.stage.module = module_;
    info.stage.pName = "main";
    info.stage.pSpecializationInfo = constants;
    info.layout = layout_;
    vk_check(vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline_),
             "vkCreateComputePipelines");
    // The module is only needed while the pipeline is created.
    vkDestroyShaderModule(device_, module_, nullptr);
    module_ = VK_NULL_HANDLE;
}

}  // namespace voxray::vulkan_detail
