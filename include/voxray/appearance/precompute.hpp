// The appearance precompute (issue 25, item 3): every non-empty voxel of a model voxelized
// from `mesh` sampled against the original triangles (appearance/voxel_sampler.hpp) on all
// threads, and a record made of what it saw. Voxels are handed out in table order and each
// one's rays depend only on (seed, voxel, ray), so the table is the same for any thread count.
// `Scene` traces the mesh in voxel space (embree/triangle_scene.hpp built on the grid map the
// voxelizer used); the model must be io::voxelize(mesh) at that grid.
#pragma once
#include <atomic>
#include <chrono>
#include <cstdint>
#include <vector>

#include "voxray/appearance/averages.hpp"
#include "voxray/appearance/table.hpp"
#include "voxray/appearance/voxel_sampler.hpp"
#include "voxray/core/error.hpp"
#include "voxray/model/build_threads.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::appearance {

struct precompute_options {
    sampling_options sampling;
    unsigned threads = 0;  // 0: every hardware thread
};

struct precompute_stats {
    std::uint64_t voxels = 0, rays = 0, hits = 0;
    double seconds = 0;
    double rays_per_second() const { return seconds > 0 ? double(rays) / seconds : 0; }
    double us_per_voxel() const { return voxels ? seconds * 1e6 / double(voxels) : 0; }
};

// The averages table of `model`'s voxels.
template <class Scene>
appearance_table precompute_averages(const Scene& scene, const io::triangle_mesh& mesh, const voxel_model& model,
                                     const precompute_options& o = {}, precompute_stats* stats = nullptr) {
    if (o.sampling.rays == 0) fail("appearance precompute: 0 sampling rays a voxel");
    auto start = std::chrono::steady_clock::now();
    appearance_table t;
    t.record_words = VX_APP_AVERAGES_WORDS;
    model.for_each_voxel([&](glm::ivec3 p, std::uint8_t) { t.voxels.push_back(p); });
    std::sort(t.voxels.begin(), t.voxels.end(), zyx_less);
    t.words.assign(t.voxels.size() * VX_APP_AVERAGES_WORDS, 0);
    unsigned threads = resolve_build_threads(o.threads, t.voxels.size());
    std::atomic<std::size_t> next{0};
    std::atomic<std::uint64_t> hits{0};
    constexpr std::size_t batch = 64;
    run_build_threads(threads, [&](unsigned) {
        voxel_samples samples;
        std::uint64_t mine = 0;
        for (std::size_t first; (first = next.fetch_add(batch)) < t.voxels.size();)
            for (std::size_t row = first; row < std::min(first + batch, t.voxels.size()); ++row) {
                sample_voxel(scene, mesh, t.voxels[row], o.sampling, samples);
                mine += samples.hits;
                auto record = averages_record(samples);
                std::copy(record.begin(), record.end(), t.words.begin() + std::ptrdiff_t(row * VX_APP_AVERAGES_WORDS));
            }
        hits += mine;
    });
    if (stats) {
        stats->voxels = t.voxels.size();
        stats->rays = stats->voxels * o.sampling.rays;
        stats->hits = hits;
        stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return t;
}

}  // namespace voxray::appearance
