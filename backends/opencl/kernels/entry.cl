/* voxray OpenCL backend: one __kernel per structure kernel, placed after the portable
 * kernel files. The host looks the entry point up as "vx_trace_" + Kernel::name
 * (kernels/kernel_ids.hpp). A new structure adds one VX_OPENCL_ENTRY line.
 *
 * One work-item traces one ray. The host rounds the global size up to a multiple of the
 * work-group size, so items past `count` do nothing. Rays and hits are the 32-byte
 * records of layout/ray_hit_layout.h, identical on host and device. */
#define VX_OPENCL_ENTRY(name)                                                            \
    __kernel void vx_trace_##name(__global const uint* blob, __global const vx_ray* rays, \
                                  __global vx_hit* hits, uint count, uint mode) {        \
        size_t i = get_global_id(0);                                                     \
        if (i < count) hits[i] = vx_##name##_trace(blob, rays[i], mode);                 \
    }

VX_OPENCL_ENTRY(dense_grid)
VX_OPENCL_ENTRY(brickmap)

/* Incremental updates (opencl/commit.hpp): one work-item per word of a commit packet
 * (layout/commit_layout.h) copies that word into the blob. The host rounds the global
 * size up to whole groups; the kernel skips items past the packet's word count. */
#include "voxray/kernels/commit.h"

__kernel void vx_commit(__global uint* blob, __global const uint* packet) {
    vx_commit_word(blob, packet, (uint)get_global_id(0));
}
