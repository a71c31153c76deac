// The appearance precompute (issue 25, item 3): every non-empty voxel of a model voxelized
// from `mesh` sampled against the original triangles (appearance/voxel_sampler.hpp,
// opacity_rays.hpp) on all threads, and a record made of what it saw; each voxel's rays meet
// only the triangles that reach it (voxel_triangles.hpp). Voxels are handed out
// in table order and each one's rays depend only on (seed, voxel, ray), so the table is the
// same for any thread count. `Scene` traces the mesh in voxel space
// (embree/triangle_scene.hpp built on the grid map the voxelizer used); the model must be
// io::voxelize(mesh) at that grid.
#pragma once
#include <atomic>
#include <chrono>
#include <cstdint>
#include <vector>

#include "voxray/appearance/averages.hpp"
#include "voxray/appearance/compact.hpp"
#include "voxray/appearance/faithful.hpp"
#include "voxray/appearance/sggx_baseline.hpp"
#include "voxray/appearance/six_directions.hpp"
#include "voxray/appearance/table.hpp"
#include "voxray/appearance/voxel_sampler.hpp"
#include "voxray/core/error.hpp"
#include "voxray/model/build_threads.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::appearance {

struct precompute_options {
    record_kind kind = record_kind::averages;
    sampling_options sampling{};
    unsigned opacity_strata = 2;  // compact: n x n parallel rays a face, per opacity direction
    unsigned threads = 0;         // 0: every hardware thread
    directional_light light{};    // six: the light its colours are lit by
    // Each voxel's rays against its own few triangles (voxel_triangles.hpp); false: every ray
    // descends the scene's BVH from the root (Embree; the peer the lists are timed against).
    bool voxel_lists = true;
};

struct precompute_stats {
    std::uint64_t voxels = 0, rays = 0, hits = 0;
    double seconds = 0;
    double rays_per_second() const { return seconds > 0 ? double(rays) / seconds : 0; }
    double us_per_voxel() const { return voxels ? seconds * 1e6 / double(voxels) : 0; }
};

// Opacity rays a voxel: each of the 13 directions enters through 1, 2 or 3 faces.
inline std::uint64_t opacity_rays_per_voxel(unsigned strata) { return 27ull * strata * strata; }

// The table of `voxels` (any order) made from what their sampling rays meet on `surfaces`
// (appearance/voxel_sampler.hpp: triangle_surfaces, or a finer level's through
// appearance/resample.hpp), in the voxel space of `voxels`.
template <class Surfaces>
appearance_table build_table(const Surfaces& surfaces, std::vector<glm::ivec3> voxels, const precompute_options& o,
                             precompute_stats* stats = nullptr) {
    if (o.sampling.rays == 0) fail("appearance precompute: 0 sampling rays a voxel");
    const bool compact = o.kind == record_kind::compact;
    if (compact && o.opacity_strata == 0) fail("appearance precompute: 0 opacity strata");
    auto start = std::chrono::steady_clock::now();
    appearance_table t;
    t.kind = o.kind;
    t.record_words = record_words(o.kind);
    if (t.record_words == 0) fail("appearance precompute: unknown record kind ", int(o.kind));
    t.voxels = std::move(voxels);
    std::sort(t.voxels.begin(), t.voxels.end(), ordinal_less);
    t.words.assign(t.voxels.size() * std::size_t(t.record_words), 0);
    std::vector<std::vector<std::uint32_t>> row_faces(compact ? t.voxels.size() : 0);
    unsigned threads = resolve_build_threads(o.threads, t.voxels.size());
    std::atomic<std::size_t> next{0};
    std::atomic<std::uint64_t> hits{0};
    constexpr std::size_t batch = 64;
    run_build_threads(threads, [&](unsigned) {
        voxel_samples samples;
        voxel_triangles near;  // the voxel's own triangles, where the surfaces are triangles
        std::uint64_t mine = 0;
        auto fill_row = [&](const auto& voxel_surfaces, std::size_t row) {
            auto* words = t.words.data() + row * std::size_t(t.record_words);
            auto store = [&](const auto& record) { std::copy(record.begin(), record.end(), words); };
            if (o.kind == record_kind::faithful) {  // the paper's own sampling of the subgrid
                faithful_samples paper = sample_faithful(voxel_surfaces, t.voxels[row], o.sampling);
                mine += paper.hits;
                return store(make_faithful_record(paper));
            }
            sample_voxel(voxel_surfaces, t.voxels[row], o.sampling, samples);
            mine += samples.hits;
            if (o.kind == record_kind::averages) return store(averages_record(samples));
            if (o.kind == record_kind::six) return store(six_directions_record(samples, o.light));
            if (o.kind == record_kind::sggx) return store(sggx_record(samples));
            directional_opacities alpha =
                directional_opacity(voxel_surfaces, t.voxels[row], o.opacity_strata, o.sampling.seed);
            compact_record r = make_compact_record(voxel_faces(samples), alpha);
            store(r.head);
            row_faces[row] = std::move(r.faces);
        };
        for (std::size_t first; (first = next.fetch_add(batch)) < t.voxels.size();)
            for (std::size_t row = first; row < std::min(first + batch, t.voxels.size()); ++row)
                if (o.voxel_lists)
                    with_voxel_surfaces(surfaces, t.voxels[row], near,
                                        [&](const auto& voxel_surfaces) { fill_row(voxel_surfaces, row); });
                else
                    fill_row(surfaces, row);
        hits += mine;
    });
    for (std::size_t row = 0; row < row_faces.size(); ++row) {  // the face pool, in row order
        t.words[row * VX_APP_COMPACT_WORDS] = std::uint32_t(t.faces.size() / VX_APP_FACE_WORDS);
        t.faces.insert(t.faces.end(), row_faces[row].begin(), row_faces[row].end());
    }
    if (t.faces.size() / VX_APP_FACE_WORDS > 0xFFFFFFFFull) fail("appearance precompute: over 2^32 faces");
    if (stats) {
        stats->voxels = t.voxels.size();
        stats->rays = stats->voxels * (o.sampling.rays + (compact ? opacity_rays_per_voxel(o.opacity_strata) : 0));
        stats->hits = hits;
        stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    return t;
}

template <class Scene>
appearance_table precompute(const Scene& scene, const io::triangle_mesh& mesh, const voxel_model& model,
                            const precompute_options& o = {}, precompute_stats* stats = nullptr) {
    mesh.validate();  // a mesh built by hand may hold what the readers refuse (a NaN vertex)
    std::vector<glm::ivec3> voxels;
    model.for_each_voxel([&](glm::ivec3 p, std::uint8_t) { voxels.push_back(p); });
    return build_table(triangle_surfaces<Scene>{scene, mesh}, std::move(voxels), o, stats);
}

}  // namespace voxray::appearance
