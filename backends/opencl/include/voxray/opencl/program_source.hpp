// One embedded OpenCL program: the structure kernel's name (kernels/kernel_tag.inc tags
// carry the same) and its flattened OpenCL C source. The generated table
// (voxray/generated/opencl_programs.hpp) lists one per voxray_add_structure call.
#pragma once
#include <string_view>

namespace voxray::opencl_detail {

struct program_source {
    std::string_view name;
    const char* source;
    // Staged (voxray_add_kernel ... STAGED): vx_closest_<name>_then and vx_any_<name>_then
    // run after the trace kernels, on their hits (entry.cl).
    bool staged = false;
};

}  // namespace voxray::opencl_detail
