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
//
// On the application's own device and buffers (vulkan/interop.hpp):
//   options.user_device = voxray::vulkan_user_device{instance, physical, device, family, queue};
//   t.closest_hit(voxray::vulkan_buffer_range{rays, offset}, voxray::vulkan_buffer_range{hits}, n);
//   t.record_closest_hit(command_buffer, rays, hits, n);   // recorded only; barriers are yours
#pragma once
// Set by the CMake target voxray::vulkan, which also brings the Vulkan loader and the
// compiled shaders: without it the program would compile and then fail to link.
#ifndef VOXRAY_LINKED_VULKAN
#error "voxray/vulkan.hpp needs the CMake target voxray::vulkan: target_link_libraries(<your target> PRIVATE voxray::vulkan), after find_package(voxray COMPONENTS vulkan) or add_subdirectory"
#endif
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
