// Compute entry point of a structure's frame passes (voxray_add_structure ... PASSES; the
// world's are world/frame/passes.h): one invocation per item of the pass in the push constants.
// VX_PASS names the structure's pass function (-DVX_PASS=vx_<name>_pass, backend.cmake).
#if !defined(VX_PASS)
#error "VX_PASS must name the structure's pass function, e.g. -DVX_PASS=vx_world_pass"
#endif

// 64 invocations a group, like the trace shaders (voxray/vulkan/pipeline.hpp).
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

// Must match voxray::vulkan_detail::pass_push (voxray/vulkan/passes.hpp): 2 addresses at
// bytes 0 and 8, then first, count and pass; 32 bytes in all. A pass of more items than
// one dispatch holds runs as several, each starting at `first`.
layout(push_constant, std430) uniform vx_pass_push {
    uvec2 blob;   // structure words
    uvec2 frame;  // frame words (world/frame/layout.h), read and written
    uint first;   // item of this dispatch's invocation 0
    uint count;   // items in this dispatch
    uint pass;    // which pass
} pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;  // the last group may be partly empty
    VX_PASS(vx_words(pc.blob), pc.frame, pc.pass, pc.first + i);
}
