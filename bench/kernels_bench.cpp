// Microbenchmarks of the portable kernels on the CPU: one thread, the dense grid and
// brickmap traversals with SIMD lanes vs scalar lanes, on camera rays over a seeded noise scene
// with a floor. Counters: rays/s and steps per ray.
#include <benchmark/benchmark.h>

#include "voxray/check/ray_sets.hpp"
#include "voxray/cpu.hpp"
#include "voxray/brickmap/brickmap.hpp"
#include "voxray/dense_grid/dense_grid.hpp"

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

using brickmap8 = voxray::brickmap<std::uint8_t, 8>;
BENCHMARK(trace_primary<voxray::cpu, voxray::dense_grid>)->Name("dense_primary/simd")->Unit(benchmark::kMillisecond);
BENCHMARK(trace_primary<voxray::cpu_scalar, voxray::dense_grid>)->Name("dense_primary/scalar")->Unit(benchmark::kMillisecond);
BENCHMARK(trace_primary<voxray::cpu, brickmap8>)->Name("brickmap_primary/simd")->Unit(benchmark::kMillisecond);
BENCHMARK(trace_primary<voxray::cpu_scalar, brickmap8>)->Name("brickmap_primary/scalar")->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
