// Which SPIR-V module traces a structure kernel. The build specializes this for every
// name in VOXRAY_KERNEL_NAMES (generated voxray/generated/vulkan_modules.hpp), so a
// kernel without a module is a compile-time error, not a run-time surprise.
#pragma once

namespace voxray::vulkan_detail {

template <class Kernel>
struct spirv_module {
    static_assert(sizeof(Kernel) == 0,
                  "no SPIR-V module for this kernel: add its name to VOXRAY_KERNEL_NAMES "
                  "(scripts/cmake/voxray_kernels.cmake)");
};

}  // namespace voxray::vulkan_detail
