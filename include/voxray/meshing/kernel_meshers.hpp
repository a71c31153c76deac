// The mesher kernel on every backend this program links (each backend target defines
// VOXRAY_LINKED_<NAME>): the one list the tool and the tests walk. The CPU's entry runs the
// kernel on its scalar lanes (cpu/chunk_mesher.hpp).
#pragma once
#include "voxray/core/type_list.hpp"
#if defined(VOXRAY_LINKED_CPU)
#include "voxray/cpu/chunk_mesher.hpp"
#endif
#if defined(VOXRAY_LINKED_OPENCL)
#include "voxray/opencl/chunk_mesher.hpp"
#endif
#if defined(VOXRAY_LINKED_VULKAN)
#include "voxray/vulkan/chunk_mesher.hpp"
#endif

namespace voxray::meshing {

using kernel_meshers = concat_type_lists_t<
#if defined(VOXRAY_LINKED_CPU)
    type_list<cpu_chunk_mesher>,
#endif
#if defined(VOXRAY_LINKED_OPENCL)
    type_list<opencl_chunk_mesher>,
#endif
#if defined(VOXRAY_LINKED_VULKAN)
    type_list<vulkan_chunk_mesher>,
#endif
    type_list<>>;

}  // namespace voxray::meshing
