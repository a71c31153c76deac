// Public entry point of the OpenCL backend (target voxray::opencl):
//   voxray::tracer<voxray::opencl, voxray::dense_grid> t(grid, {.device = "pthread"});
#pragma once
// Set by the CMake target voxray::opencl (which brings the OpenCL library and the kernel
// sources): without it the program would compile and then fail to link.
#ifndef VOXRAY_LINKED_OPENCL
#error "voxray/opencl.hpp needs the CMake target voxray::opencl: target_link_libraries(<your target> PRIVATE voxray::opencl), after find_package(voxray COMPONENTS opencl) or add_subdirectory"
#endif
#include "voxray/opencl/backend.hpp"
#include "voxray/tracer.hpp"
