// One embedded OpenCL program: the structure kernel's name (kernels/kernel_tag.inc tags
// carry the same) and its flattened OpenCL C source. The generated table
// (voxray/generated/opencl_programs.hpp) lists one per voxray_add_structure call.
#pragma once
#include <string_view>

namespace voxray::opencl_detail {

struct program_source {
    std::string_view name;
    const char* source;
};

}  // namespace voxray::opencl_detail
