// Compute entry point of the commit shader (voxray/vulkan/commit.hpp): one invocation per
// word of a commit packet (sync/commit_layout.h) copies that word into the structure
// blob. Follows backends/vulkan/shaders/preamble.glsl and the flattened sync/commit.h.

// 64 invocations a group, like the trace shaders; the host uses the same number.
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

// Must match voxray::vulkan_detail::commit_push (voxray/vulkan/commit.hpp): 2 addresses at
// bytes 0 and 8, then `first` at 16; 24 bytes in all. A packet larger than one dispatch
// (maxComputeWorkGroupCount x 64 words) is committed by several, each starting at `first`.
layout(push_constant, std430) uniform vx_commit_push {
    uvec2 blob;    // structure words, written
    uvec2 packet;  // the commit packet, read
    uint first;    // packet data word of this dispatch's invocation 0
} pc;

void main() {
    // Items past the packet's word count return inside vx_commit_word.
    vx_commit_word(vx_words_rw(pc.blob), vx_words(pc.packet), pc.first + gl_GlobalInvocationID.x);
}
