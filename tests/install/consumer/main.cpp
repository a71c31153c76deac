// Traces one ray on every backend target the consumer linked and checks that each finds
// the one voxel; checks the version macros against the version voxray was configured with.
#include <cmath>
#include <cstdio>
#include <cstring>

#include "voxray/dense_grid/dense_grid.hpp"
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

template <class Backend>
bool trace_one(const voxray::dense_grid& grid) {
    voxray::tracer<Backend, voxray::dense_grid> tracer(grid);
    voxray::ray r{{1.5f, 1.5f, -5.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, INFINITY};
    voxray::hit h;
    tracer.closest_hit({&r, 1}, {&h, 1});
    bool ok = h.is_hit() && h.material == 42 && h.t == 8.0f && h.voxel == glm::ivec3(1, 1, 3);
    std::printf("%s: t=%.1f %s\n", Backend::name, h.t, ok ? "ok" : "WRONG");
    return ok;
}

int main() {
    voxray::voxel_model model;
    model.set({1, 1, 3}, 42);
    voxray::dense_grid grid(model);
    bool ok = std::strcmp(VOXRAY_VERSION_STRING, EXPECT_VERSION) == 0;
    std::printf("voxray %s (configured as %s)\n", VOXRAY_VERSION_STRING, EXPECT_VERSION);
#if CONSUMER_WITH_CPU
    ok = trace_one<voxray::cpu>(grid) && ok;
#endif
#if CONSUMER_WITH_OPENCL
    ok = trace_one<voxray::opencl>(grid) && ok;
#endif
#if CONSUMER_WITH_VULKAN
    ok = trace_one<voxray::vulkan>(grid) && ok;
#endif
    return ok ? 0 : 1;
}
