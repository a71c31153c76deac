// voxray::vulkan — the Vulkan compute backend. Use it as the first argument of tracer:
//
//   #include <voxray/vulkan.hpp>
//   voxray::vulkan_options options;
//   options.device = "llvmpipe";                        // optional: pick a device by name
//   voxray::tracer<voxray::vulkan, voxray::dense_grid> t(grid, options);
//   t.closest_hit(rays, hits);
//
// The kernels are compiled to SPIR-V when voxray is built and embedded in headers; at
// run time it needs a Vulkan 1.2 driver with bufferDeviceAddress (any current GPU
// driver, or Mesa's lavapipe on the CPU). Structures are not limited by
// maxStorageBufferRange: the shaders reach them by buffer device address.
#pragma once
#include "voxray/tracer.hpp"
#include "voxray/vulkan/engine.hpp"
#include "voxray/vulkan/options.hpp"

namespace voxray {

struct vulkan {
    using options = vulkan_options;
    template <class Kernel>
    using engine = vulkan_detail::engine<Kernel>;
    static constexpr const char* name = "vulkan";
};

}  // namespace voxray
