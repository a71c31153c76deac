// Public entry point of the OpenCL backend (target voxray::opencl):
//   voxray::tracer<voxray::opencl, voxray::dense_grid> t(grid, {.device = "pthread"});
// On the application's own context, queue and buffers (opencl/interop.hpp):
//   options.user_context = voxray::opencl_user_context{context, device, queue};
//   t.closest_hit(ray_mem, hit_mem, n);   // enqueued on that queue; its order synchronises
#pragma once
// Set by the CMake target voxray::opencl (which brings the OpenCL library and the kernel
// sources): without it the program would compile and then fail to link.
#ifndef VOXRAY_LINKED_OPENCL
#error "voxray/opencl.hpp needs the CMake target voxray::opencl: target_link_libraries(<your target> PRIVATE voxray::opencl), after find_package(voxray COMPONENTS opencl) or add_subdirectory"
#endif
#include "voxray/opencl/backend.hpp"
#include "voxray/tracer.hpp"
