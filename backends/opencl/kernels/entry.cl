/* voxray OpenCL backend: the kernels of one structure program, placed after the portable
 * kernel files; the build appends one VX_OPENCL_ENTRY(<name>) line per program
 * (voxray_add_structure). The host looks them up as vx_closest_<name> and vx_any_<name>
 * (opencl/engine.hpp): the trace mode is a constant in each, so each compiles to its own
 * code and any-hit skips what it need not read.
 *
 * One work-item traces one ray. The host rounds the global size up to a multiple of the
 * work-group size, so items past `count` do nothing. Rays and hits are the 32-byte
 * records of core/ray_hit_layout.h, identical on host and device. */
#define VX_OPENCL_ENTRY_MODE(name, prefix, mode)                                              \
    __kernel void prefix##name(__global const uint* blob, __global const vx_ray* rays,        \
                               __global vx_hit* hits, uint count) {                           \
        size_t i = get_global_id(0);                                                          \
        if (i < count) hits[i] = vx_##name##_trace(blob, rays[i], mode);                      \
    }
#define VX_OPENCL_ENTRY(name)                                 \
    VX_OPENCL_ENTRY_MODE(name, vx_closest_, VX_MODE_CLOSEST)  \
    VX_OPENCL_ENTRY_MODE(name, vx_any_, VX_MODE_ANY)

/* A staged kernel (voxray_add_kernel ... STAGED): vx_closest_<name> runs its first stage
 * and vx_closest_<name>_then its second on the hits the first wrote, enqueued one after the
 * other (opencl/engine.hpp). Separate kernels compile separately: the first stage's code
 * does not carry the second's. */
#define VX_OPENCL_STAGED_ENTRY_MODE(name, prefix, mode)                                         \
    __kernel void prefix##name(__global const uint* blob, __global const vx_ray* rays,          \
                               __global vx_hit* hits, uint count) {                             \
        size_t i = get_global_id(0);                                                            \
        if (i < count) hits[i] = vx_##name##_first(blob, rays[i], mode);                        \
    }                                                                                           \
    __kernel void prefix##name##_then(__global const uint* blob, __global const vx_ray* rays,   \
                                      __global vx_hit* hits, uint count) {                      \
        size_t i = get_global_id(0);                                                            \
        if (i < count) hits[i] = vx_##name##_then(blob, rays[i], hits[i], mode);                \
    }
#define VX_OPENCL_STAGED_ENTRY(name)                                 \
    VX_OPENCL_STAGED_ENTRY_MODE(name, vx_closest_, VX_MODE_CLOSEST)  \
    VX_OPENCL_STAGED_ENTRY_MODE(name, vx_any_, VX_MODE_ANY)

/* A structure's frame passes (voxray_add_structure ... PASSES; the world's are
 * world/frame/passes.h), looked up as vx_pass_<name>: one work-item per item of `pass`. */
#define VX_OPENCL_PASS_ENTRY(name)                                                            \
    __kernel void vx_pass_##name(__global const uint* blob, __global uint* frame, uint pass,  \
                                 uint count) {                                                \
        uint i = (uint)get_global_id(0);                                                      \
        if (i < count) vx_##name##_pass(blob, frame, pass, i);                                \
    }
