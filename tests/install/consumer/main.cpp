// Traces one ray on every installed backend and checks that they agree.
#include <cstdio>

#include "voxray/cpu.hpp"
#include "voxray/opencl.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/vulkan.hpp"

template <class Backend>
voxray::hit trace_one(const voxray::dense_grid& grid) {
    voxray::tracer<Backend, voxray::dense_grid> tracer(grid);
    voxray::ray r{{1.5f, 1.5f, -5.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, INFINITY};
    voxray::hit h;
    tracer.closest_hit({&r, 1}, {&h, 1});
    return h;
}

int main() {
    voxray::voxel_model model;
    model.set({1, 1, 3}, 42);
    voxray::dense_grid grid(model);
    voxray::hit a = trace_one<voxray::cpu>(grid), b = trace_one<voxray::opencl>(grid), c = trace_one<voxray::vulkan>(grid);
    bool ok = a.is_hit() && a.material == 42 && a.t == 8.0f && b.t == a.t && c.t == a.t && b.voxel == a.voxel &&
              c.voxel == a.voxel;
    std::printf("cpu t=%.1f opencl t=%.1f vulkan t=%.1f: %s\n", a.t, b.t, c.t, ok ? "agree" : "DISAGREE");
    return ok ? 0 : 1;
}
