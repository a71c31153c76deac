// The compute pipeline of one structure kernel: its embedded SPIR-V, a layout with push
// constants only (buffers are reached by device address, so there are no descriptors),
// and the push constant record that must match backends/vulkan/shaders/entry.glsl.
#pragma once
#include <bit>
#include <cstddef>
#include <cstdint>
#include <span>

#include <vulkan/vulkan.h>

#include "voxray/core/host_code.hpp"
#include "voxray/vulkan/check.hpp"
#include "voxray/vulkan/device.hpp"

namespace voxray::vulkan_detail {

// Invocations per workgroup of the commit and pass shaders (local_size_x = 64), and the
// trace shader's default (entry.glsl; a specialization constant there, trace_group_size_id).
inline constexpr std::uint32_t group_size = 64;

// Addresses are 64-bit; the shader reads each as a uvec2 (low word first), which is the
// same bytes on a little-endian host. std430 puts the fields at these offsets.
struct push_constants {
    std::uint64_t blob;
    std::uint64_t rays;
    std::uint64_t hits;
    std::uint32_t count;
    std::uint32_t unused;  // the trace mode is a specialization constant of each pipeline
};
static_assert(std::endian::native == std::endian::little, "addresses are passed as (low, high) word pairs");
static_assert(sizeof(push_constants) == 32);
static_assert(offsetof(push_constants, rays) == 8 && offsetof(push_constants, hits) == 16);
static_assert(offsetof(push_constants, count) == 24 && offsetof(push_constants, unused) == 28);

// The trace shaders' specialization constant that holds the mode (entry.glsl, constant_id 0).
inline constexpr std::uint32_t trace_mode_constant_id = 0;
// The trace shaders' specialization constant that holds the workgroup size (local_size_x_id 1).
inline constexpr std::uint32_t trace_group_size_id = 1;
// A trace pipeline's mode (VX_MODE_CLOSEST or VX_MODE_ANY), fixed when it is created.
struct trace_mode {
    std::uint32_t value;
};

class compute_pipeline {
public:
    // `push_bytes`: size of the push constant record its shader declares (the commit and
    // pass shaders have their own).
    compute_pipeline(const context& ctx, std::span<const std::uint32_t> spirv, std::uint32_t push_bytes);
    // A trace shader's pipeline (push_constants above) for one trace mode and workgroup size.
    compute_pipeline(const context& ctx, std::span<const std::uint32_t> spirv, trace_mode mode,
                     std::uint32_t invocations);
    ~compute_pipeline() { destroy(); }
    compute_pipeline(const compute_pipeline&) = delete;
    compute_pipeline& operator=(const compute_pipeline&) = delete;

    template <class Push>
    void bind(VkCommandBuffer cmd, const Push& pc) const {
        if (sizeof(Push) != push_bytes_)
            fail("vulkan: push constants of ", sizeof(Push), " bytes for a pipeline made for ", push_bytes_);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline_);
        vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(pc), &pc);
    }

private:
    void create(std::span<const std::uint32_t> spirv, const VkSpecializationInfo* constants);

    void destroy() {
        if (pipeline_) vkDestroyPipeline(device_, pipeline_, nullptr);
        if (layout_) vkDestroyPipelineLayout(device_, layout_, nullptr);
        if (module_) vkDestroyShaderModule(device_, module_, nullptr);
        pipeline_ = VK_NULL_HANDLE;
        layout_ = VK_NULL_HANDLE;
        module_ = VK_NULL_HANDLE;
    }

    VkDevice device_;
    std::uint32_t push_bytes_;
    VkShaderModule module_ = VK_NULL_HANDLE;
    VkPipelineLayout layout_ = VK_NULL_HANDLE;
    VkPipeline pipeline_ = VK_NULL_HANDLE;
};

}  // namespace voxray::vulkan_detail

// The definitions: here, or compiled once in voxray::kernels (core/host_code.hpp).
#if VOXRAY_HOST_DEFINITIONS
#include "voxray/vulkan/detail/pipeline.hpp"
#endif
