// Compute entry point of the compositing walk (appearance/walk.inc): one invocation per ray,
// after one structure's kernel, the appearance dialect and the walk instantiated over that
// kernel's closest hit as vx_app_walk (cmake/voxray_kernels.cmake writes that part). One
// module per structure, <structure>_appearance (vulkan/appearance_walk.hpp).

// 64 invocations a group, like the trace shaders (voxray/vulkan/pipeline.hpp).
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer vx_app_rays { vx_ray r[]; };
// 64-byte records of 32-bit scalars (appearance/pixel_layout.h): their std430 layout too.
layout(buffer_reference, std430, buffer_reference_align = 4) writeonly buffer vx_app_pixels { vx_app_walk_result p[]; };

// Must match voxray::vulkan_detail::appearance_push (vulkan/appearance_walk.hpp): six
// addresses at bytes 0..40, the light at 48, then cutoff, max_visits, kind, count and
// shadows_at.
layout(push_constant, std430) uniform vx_app_push {
    uvec2 blob;     // structure words
    uvec2 index;    // ordinal index (appearance/ordinal_layout.h)
    uvec2 records;  // the table's records
    uvec2 faces;    // the compact records' face pool
    uvec2 rays;     // vx_ray[count]
    uvec2 pixels;   // vx_app_walk_result[count]
    vec4 light;     // towards the light (unit), ambient
    float cutoff;
    uint max_visits;
    uint kind;      // VX_APP_KIND_*
    uint count;     // rays in this dispatch
    uint shadows_at;  // where the shadows start in records; 0: none (appearance/walk.inc)
} pc;

void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= pc.count) return;  // the last group may be partly empty
    vx_app_light light;
    light.lx = pc.light.x, light.ly = pc.light.y, light.lz = pc.light.z, light.ambient = pc.light.w;
    vx_app_pixels(pc.pixels).p[i] = vx_app_walk(vx_words(pc.blob), vx_words(pc.index), vx_words(pc.records),
                                                vx_words(pc.faces), pc.kind, vx_app_rays(pc.rays).r[i], light,
                                                pc.cutoff, pc.max_visits, pc.shadows_at, vx_app_walk_state_start()).w;
}
