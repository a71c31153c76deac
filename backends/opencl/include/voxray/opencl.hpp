// Public entry point of the OpenCL backend (target voxray::opencl):
//   voxray::tracer<voxray::opencl, voxray::dense_grid> t(grid, {.device = "pthread"});
#pragma once
#include "voxray/opencl/backend.hpp"
#include "voxray/tracer.hpp"
