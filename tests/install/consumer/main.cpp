// Traces one ray on every backend target the consumer linked and checks that each finds
// the one voxel, in a dense grid and in an edited NAADF (whose build and edit are host
// code: compiled here, or linked from voxray::kernels); checks the version macros
// against the version voxray was configured with.
#include <cmath>
#include <cstdio>
#include <cstring>

#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/naadf/naadf.hpp"
#include "voxray/version.hpp"
#if CONSUMER_WITH_CPU
#include "voxray/cpu.hpp"
#endif
#if CONSUMER_WITH_OPENCL
#include "voxray/opencl.hpp"
#endif
#if CONSUMER_WITH_VULKAN
#include "voxray/vulkan.hpp"
#endif

#if !defined(__x86_64__) || !CONSUMER_WITH_CPU || defined(__AVX2__)
#else
#error "voxray::cpu did not add its default -march=x86-64-v3"
#endif

static_assert(VOXRAY_VERSION == VOXRAY_VERSION_MAJOR * 10000 + VOXRAY_VERSION_MINOR * 100 + VOXRAY_VERSION_PATCH);

template <class Backend, class Structure>
bool trace_one(const Structure& structure, int z) {
    voxray::tracer<Backend, Structure> tracer(structure);
    voxray::ray r{{1.5f, 1.5f, -5.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, INFINITY};
    voxray::hit h;
    tracer.closest_hit({&r, 1}, {&h, 1});
    bool ok = h.is_hit() && h.material == 42 && h.t == float(z + 5) && h.voxel == glm::ivec3(1, 1, z);
    std::printf("%s, %s: t=%.1f %s\n", Backend::name, Structure::name.data(), h.t, ok ? "ok" : "WRONG");
    return ok;
}

template <class Backend>
bool trace_both(const voxray::dense_grid& grid, const voxray::naadf& edited) {
    return trace_one<Backend>(grid, 3) && trace_one<Backend>(edited, 2);
}

int main() {
    voxray::voxel_model model;
    model.set({1, 1, 3}, 42);
    voxray::dense_grid grid(model);
    voxray::naadf edited(model);
    edited.set({1, 1, 2}, 42);
    bool ok = std::strcmp(VOXRAY_VERSION_STRING, EXPECT_VERSION) == 0;
    std::printf("voxray %s (configured as %s)\n", VOXRAY_VERSION_STRING, EXPECT_VERSION);
#if CONSUMER_WITH_CPU
    ok = trace_both<voxray::cpu>(grid, edited) && ok;
#endif
#if CONSUMER_WITH_OPENCL
    ok = trace_both<voxray::opencl>(grid, edited) && ok;
#endif
#if CONSUMER_WITH_VULKAN
    ok = trace_both<voxray::vulkan>(grid, edited) && ok;
#endif
    return ok ? 0 : 1;
}
