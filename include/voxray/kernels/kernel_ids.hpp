// One tag per traversal kernel. A structure names its kernel with `using kernel = ...`;
// backends use the tag to pick the C++ function, the OpenCL entry point
// (vx_trace_<name>) or the SPIR-V module.
#pragma once

namespace voxray::kernels {

struct dense_grid_kernel {
    static constexpr const char* name = "dense_grid";
};

struct brickmap_kernel {
    static constexpr const char* name = "brickmap";
};

}  // namespace voxray::kernels
