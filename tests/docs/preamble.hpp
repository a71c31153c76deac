// What every fragment of the documents' code blocks may use without declaring it (see
// extract_blocks.cmake and docs/style.md, "Code blocks in the documents"). Declarations
// only: the blocks are compiled with -fsyntax-only, never linked or run.
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/model/voxel_model.hpp"

extern voxray::voxel_model model;      // a scene
extern std::vector<voxray::ray> rays;  // rays to trace
extern std::vector<voxray::hit> hits;  // one hit per ray

#if defined(VOXRAY_LINKED_VULKAN)
#include <vulkan/vulkan.h>
// The application's own Vulkan objects (guide: "Your own device and buffers").
extern VkInstance instance;
extern VkPhysicalDevice physical_device;
extern VkDevice device;
extern std::uint32_t queue_family;
extern VkQueue queue;
extern VkBuffer ray_buffer, hit_buffer;
extern VkCommandBuffer command_buffer;
#endif

#if defined(VOXRAY_LINKED_OPENCL)
#include <CL/cl.h>
// The application's own OpenCL objects.
extern cl_context context;
extern cl_device_id cl_device;
extern cl_command_queue cl_queue;
extern cl_mem ray_mem, hit_mem;
#endif
