// Compute entry point shared by every structure: one invocation per ray. The structure's
// trace function comes from the compiler command line (-DVX_TRACE=vx_<name>_trace, see
// backends/vulkan/backend.cmake), so this one file serves them all. The trace mode is a
// specialization constant: one module per structure, and the driver folds the mode into
// each of its two pipelines (voxray/vulkan/pipeline.hpp), so any-hit still compiles to
// its own code.
#if !defined(VX_TRACE)
#error "VX_TRACE must name the structure's trace function, e.g. -DVX_TRACE=vx_dense_grid_trace"
#endif

// Must match voxray::vulkan_detail::trace_mode_constant_id (voxray/vulkan/pipeline.hpp).
layout(constant_id = 0) const uint vx_trace_mode = VX_MODE_CLOSEST;

// 64 invocations a group by default: a multiple of every common subgroup size (8 on
// lavapipe, 32 on NVIDIA, 64 on AMD). A specialization constant (id 1, must match
// trace_group_size_id in voxray/vulkan/pipeline.hpp), so vulkan_options::group_size can
// tune it per device without another module.
layout(local_size_x = 64, local_size_x_id = 1, local_size_y = 1, local_size_z = 1) in;

// Ray and hit records are 32 bytes of 32-bit scalars (core/ray_hit_layout.h), which is
// also their std430 layout, so the kernel structs map onto the buffers directly. The host
// checks that both buffers start 16-byte aligned, which lets the compiler use vector loads.
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer vx_ray_buffer { vx_ray r[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) writeonly buffer vx_hit_buffer { vx_hit h[]; };

// Must match voxray::vulkan_detail::push_constants (voxray/vulkan/pipeline.hpp):
// 3 addresses at bytes 0, 8, 16, then count at 24 (the host's record pads to 32 bytes).
layout(push_constant, std430) uniform vx_push {
    uvec2 blob;   // structure words
    uvec2 rays;   // vx_ray[count]
    uvec2 hits;   // vx_hit[count]
    uint count;   // rays in this dispatch
} pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;  // the last group may be partly empty
    vx_words blob = vx_words(pc.blob);
    vx_ray_buffer rays = vx_ray_buffer(pc.rays);
    vx_hit_buffer hits = vx_hit_buffer(pc.hits);
    hits.h[i] = VX_TRACE(blob, rays.r[i], vx_trace_mode);
}
