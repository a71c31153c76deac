// voxray::cpu linked with VOXRAY_CPU_ARCH=none: no -march from voxray, so this file sees
// the compiler's baseline ISA (x86-64: no AVX2), and the tracer still works (its SIMD lanes
// are compiled by target pragmas and chosen at run time).
#include <cmath>
#include <cstdio>

#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"

#if defined(__x86_64__) && defined(__AVX2__)
#error "VOXRAY_CPU_ARCH=none still compiled this file with AVX2 (-march from voxray::cpu?)"
#endif

int main() {
    voxray::voxel_model model;
    model.set({1, 1, 3}, 42);
    voxray::dense_grid grid(model);
    voxray::tracer<voxray::cpu, voxray::dense_grid> tracer(grid);
    voxray::ray r{{1.5f, 1.5f, -5.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, INFINITY};
    voxray::hit h;
    tracer.closest_hit({&r, 1}, {&h, 1});
    bool ok = h.is_hit() && h.t == 8.0f && h.material == 42;
    std::printf("cpu without -march: t=%.1f simd width %u: %s\n", h.t, tracer.engine().simd_width(), ok ? "ok" : "WRONG");
    return ok ? 0 : 1;
}
