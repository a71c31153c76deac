/* Incremental updates (opencl/commit.hpp), a program of its own: one work-item per word of
 * a commit packet (sync/commit_layout.h) copies that word into the blob. The host rounds
 * the global size up to whole groups; the kernel skips items past the packet's word count. */
__kernel void vx_commit(__global uint* blob, __global const uint* packet) {
    vx_commit_word(blob, packet, (uint)get_global_id(0));
}
