// A whole scene as chunk meshes, for the tool's mesh commands: every 64^3 chunk that holds
// a voxel, read from the model and meshed on `threads` threads, each with its own mesher,
// then the squashed-face pass where asked.
#pragma once
#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "voxray/meshing/chunk_source.hpp"
#include "voxray/meshing/mesher.hpp"
#include "voxray/meshing/rounded.hpp"
#include "voxray/meshing/squashed.hpp"

namespace voxray::tool {

struct meshed_scene {
    std::vector<meshing::chunk_mesh> meshes;  // in meshing::chunk_origins() order
    double seconds = 0;                       // wall time of reading and meshing
};

// Calls work(i, worker) for i in [0, count) on `threads` threads; worker < threads.
template <class F>
void parallel_for(std::size_t count, unsigned threads, F&& work) {
    threads = std::max(1u, std::min<unsigned>(threads, unsigned(std::max<std::size_t>(count, 1))));
    std::atomic<std::size_t> next{0};
    auto run = [&](unsigned worker) {
        for (std::size_t i; (i = next++) < count;) work(i, worker);
    };
    std::vector<std::thread> pool;
    for (unsigned t = 1; t < threads; ++t) pool.emplace_back(run, t);
    run(0);
    for (auto& t : pool) t.join();
}

inline meshed_scene mesh_scene(const voxel_model& model, const meshing::mesher_options& options, bool squashed,
                               unsigned threads) {
    auto start = std::chrono::steady_clock::now();
    auto origins = meshing::chunk_origins(model);
    meshed_scene scene;
    scene.meshes.resize(origins.size());
    threads = std::max(1u, threads);
    std::vector<meshing::mesher> meshers(threads, meshing::mesher(options));
    std::vector<meshing::chunk_voxels> chunks(threads);
    std::vector<std::vector<std::uint8_t>> scratch(threads);
    parallel_for(origins.size(), threads, [&](std::size_t i, unsigned w) {
        meshing::fill_chunk(model, origins[i], chunks[w], scratch[w]);
        meshers[w].mesh(chunks[w], scene.meshes[i]);
        if (squashed) meshing::remove_squashed_faces(scene.meshes[i]);
    });
    scene.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return scene;
}

// Quads drawn and overdraw at one level of detail over every chunk.
struct level_figures {
    std::uint64_t quads = 0;
    meshing::overdraw_count overdraw;
};

inline level_figures figures_at(const std::vector<meshing::chunk_mesh>& meshes, int level) {
    level_figures f;
    for (auto& m : meshes) {
        f.quads += m.drawn(level);
        auto o = meshing::overdraw(m, level);
        f.overdraw.cells += o.cells, f.overdraw.covered_sum += o.covered_sum;
    }
    return f;
}

// Unit faces the quads cover (the canonical face count).
inline std::uint64_t covered_faces(const meshing::chunk_mesh& m) {
    std::uint64_t faces = 0;
    for (std::uint32_t i = 0; i < m.quad_count(); ++i) {
        auto q = m.at(i);
        faces += std::uint64_t(q.w) * std::uint64_t(q.h);
    }
    return faces;
}

}  // namespace voxray::tool
