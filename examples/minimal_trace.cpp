// The smallest use of voxray: build a model, build the reference grid, trace one ray.
// Swapping voxray::cpu for voxray::opencl or voxray::vulkan (and linking that target)
// is the only change needed to run the same trace on another backend.
#include <cstdio>

#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"

int main() {
    voxray::voxel_model model;
    for (int x = 0; x < 8; ++x) model.set({x, 0, 4}, 3);

    voxray::dense_grid grid(model);
    voxray::tracer<voxray::cpu, voxray::dense_grid> tracer(grid);

    voxray::ray r{{4.5f, 0.5f, -10.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, INFINITY};
    voxray::hit h;
    tracer.closest_hit({&r, 1}, {&h, 1});
    std::printf("hit=%d t=%.2f voxel=(%d,%d,%d) face=%s material=%u\n", h.is_hit(), h.t, h.voxel.x, h.voxel.y,
                h.voxel.z, voxray::face_name(h.normal), h.material);
    return h.is_hit() ? 0 : 1;
}
