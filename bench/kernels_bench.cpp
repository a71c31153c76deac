// Microbenchmarks of the portable kernels on the CPU: one thread, the dense grid and
// brickmap traversals with SIMD lanes vs scalar lanes, on camera rays over a seeded noise scene
// with a floor; and NAADF's fixed cost a ray (set-up, lookup, stream refill, hit record) on
// rays of 0 and 1 steps. Counters: rays/s, time per ray and steps per ray.
#include <benchmark/benchmark.h>

#include "voxray/check/ray_sets.hpp"
#include "voxray/cpu.hpp"
#include "voxray/brickmap/brickmap.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/naadf/naadf.hpp"

namespace {

const voxray::voxel_model& scene() {
    static voxray::voxel_model model = [] {
        voxray::voxel_model m;
        voxray::rng g(5);
        for (int x = 0; x < 256; ++x)
            for (int y = 0; y < 256; ++y) {
                m.set({x, y, 0}, 1);
                if (g.uniform() < 0.02f)
                    for (int z = 1; z < 2 + g.below(40); ++z) m.set({x, y, z}, std::uint8_t(2 + g.below(200)));
            }
        return m;
    }();
    return model;
}

template <class Backend, class Structure>
void trace_primary(benchmark::State& state) {
    Structure structure(scene());
    voxray::tracer<Backend, Structure> tracer(structure, voxray::cpu_options{1});
    auto rays = voxray::primary_rays(voxray::auto_camera(scene().bounds(), 2), 256, 256);
    std::vector<voxray::hit> hits(rays.size());
    for (auto _ : state) {
        tracer.closest_hit(rays, hits);
        benchmark::DoNotOptimize(hits.data());
    }
    double steps = 0;
    for (auto& h : hits) steps += h.steps;
    state.counters["rays/s"] = benchmark::Counter(double(rays.size()) * state.iterations(), benchmark::Counter::kIsRate);
    state.counters["steps/ray"] = steps / double(hits.size());
}

// Rays that start on the scene's floor (z = 0 is solid everywhere) at random points,
// in random downward directions: `steps` 0 starts inside the floor voxel (a hit at the
// first lookup), 1 starts in the empty voxel above it (one move, then the hit). What such
// a ray costs is the structure's fixed cost a ray, the refill of the stream included.
std::vector<voxray::ray> floor_rays(int steps) {
    voxray::rng g(11);
    std::vector<voxray::ray> rays(1 << 18);
    for (auto& r : rays) {
        glm::vec3 d = glm::normalize(glm::vec3(g.uniform(-1, 1), g.uniform(-1, 1), -1.0f));
        r = {{g.uniform(8, 248), g.uniform(8, 248), steps == 0 ? 0.5f : 1.5f}, 0.0f, d, INFINITY};
    }
    return rays;
}

template <class Backend, int Steps, bool AnyHit>
void naadf_fixed_cost(benchmark::State& state) {
    voxray::naadf structure(scene());
    voxray::tracer<Backend, voxray::naadf> tracer(structure, voxray::cpu_options{1});
    auto rays = floor_rays(Steps);
    std::vector<voxray::hit> hits(rays.size());
    for (auto _ : state) {
        if (AnyHit) tracer.any_hit(rays, hits);
        else tracer.closest_hit(rays, hits);
        benchmark::DoNotOptimize(hits.data());
    }
    double steps = 0;
    for (auto& h : hits) steps += h.steps;
    double count = double(rays.size()) * double(state.iterations());
    state.counters["rays/s"] = benchmark::Counter(count, benchmark::Counter::kIsRate);
    state.counters["time/ray"] = benchmark::Counter(count, benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
    state.counters["steps/ray"] = steps / double(hits.size());
}

using brickmap8 = voxray::brickmap<std::uint8_t, 8>;
BENCHMARK(trace_primary<voxray::cpu, voxray::dense_grid>)->Name("dense_primary/simd")->Unit(benchmark::kMillisecond);
BENCHMARK(trace_primary<voxray::cpu_scalar, voxray::dense_grid>)->Name("dense_primary/scalar")->Unit(benchmark::kMillisecond);
BENCHMARK(trace_primary<voxray::cpu, brickmap8>)->Name("brickmap_primary/simd")->Unit(benchmark::kMillisecond);
BENCHMARK(trace_primary<voxray::cpu_scalar, brickmap8>)->Name("brickmap_primary/scalar")->Unit(benchmark::kMillisecond);

BENCHMARK(naadf_fixed_cost<voxray::cpu, 0, false>)->Name("naadf_fixed_cost/0_steps/closest/simd");
BENCHMARK(naadf_fixed_cost<voxray::cpu, 1, false>)->Name("naadf_fixed_cost/1_step/closest/simd");
BENCHMARK(naadf_fixed_cost<voxray::cpu, 0, true>)->Name("naadf_fixed_cost/0_steps/any/simd");
BENCHMARK(naadf_fixed_cost<voxray::cpu, 1, true>)->Name("naadf_fixed_cost/1_step/any/simd");
BENCHMARK(naadf_fixed_cost<voxray::cpu_scalar, 0, false>)->Name("naadf_fixed_cost/0_steps/closest/scalar");
BENCHMARK(naadf_fixed_cost<voxray::cpu_scalar, 1, false>)->Name("naadf_fixed_cost/1_step/closest/scalar");

}  // namespace

BENCHMARK_MAIN();
