// The checks of `voxray check SCENE --mesh`, each a count of mismatches:
//  - every chunk's canonical face set (quads expanded to unit faces, AO on) against brute
//    force over its voxels, and its POP order and table;
//  - closedness at every level of detail over all chunks, and the squashed-face pass
//    leaving every plane's coverage as it was;
//  - shared vertices and T-vertices after morphing over --mesh-views random views (a
//    sample of at most 5,000 shared vertices and 20,000 T-junctions on large scenes);
//  - the mesher kernel on every backend against the CPU mesher, word for word (on at most
//    --mesh-kernel-chunks chunks: lavapipe takes about 0.2 s a chunk);
//  - the Vulkan raster path at level 0 against the ray tracer's primary hits (mesh_raster.hpp).
#include "mesh_check.hpp"

#include <algorithm>
#include <cstdio>

#include "mesh_raster.hpp"
#include "mesh_scene.hpp"
#include "voxray/check/mesh_cracks.hpp"
#include "voxray/check/mesh_faces.hpp"
#include "voxray/meshing/kernel_meshers.hpp"

namespace voxray::tool {

namespace {

template <class T>
void keep_sample(std::vector<T>& v, std::size_t most, std::uint64_t seed) {
    if (v.size() <= most) return;
    scenes::rng g{seed};
    for (std::size_t i = 0; i < most; ++i) std::swap(v[i], v[i + std::size_t(g.next() % (v.size() - i))]);
    v.resize(most);
}

// The chunks the mesher kernel gives on each backend (meshing/kernel.h) against the CPU
// mesher's `meshes` (AO on, before the squashed-face pass), on at most `most` chunks evenly
// spread: chunks whose words or table differ.
std::uint64_t check_kernel(const voxel_model& model, const std::vector<glm::ivec3>& all_origins,
                           const std::vector<meshing::chunk_mesh>& all_meshes, std::size_t most) {
    constexpr std::size_t batch = 8;
    std::vector<glm::ivec3> origins;
    std::vector<meshing::chunk_mesh> meshes;
    std::size_t n = std::min(most, all_origins.size());
    for (std::size_t i = 0; i < n; ++i) {
        origins.push_back(all_origins[i * all_origins.size() / n]);
        meshes.push_back(all_meshes[i * all_origins.size() / n]);
    }
    std::uint64_t differing_all = 0;
    for_each_type(meshing::kernel_meshers{}, [&]<class Mesher>() {
        Mesher kernel({.ambient_occlusion = true});
        std::uint64_t differing = 0;
        std::vector<meshing::chunk_voxels> chunks;
        std::vector<std::uint8_t> scratch;
        for (std::size_t first = 0; first < origins.size(); first += batch) {
            std::size_t n = std::min(batch, origins.size() - first);
            chunks.resize(n);
            std::uint32_t most = 1;  // the frame only as large as this batch needs
            for (std::size_t i = 0; i < n; ++i) {
                meshing::fill_chunk(model, origins[first + i], chunks[i], scratch);
                most = std::max(most, meshes[first + i].quad_count());
            }
            std::vector<meshing::chunk_mesh> got = kernel.mesh(chunks, most);
            for (std::size_t i = 0; i < n; ++i)
                differing += got[i].words != meshes[first + i].words || got[i].table != meshes[first + i].table;
        }
        std::printf("mesher kernel on %s: %zu of %zu chunks, %llu differing from the CPU mesher\n",
                    kernel.device_name().c_str(), origins.size(), all_origins.size(), (unsigned long long)differing);
        differing_all += differing;
    });
    return differing_all;
}

}  // namespace

std::uint64_t check_mesh(const voxel_model& model, const mesh_check_options& o) {
    auto origins = meshing::chunk_origins(model);
    std::vector<meshing::chunk_mesh> meshes(origins.size());
    std::vector<std::uint64_t> face_mismatches(origins.size()), order_problems(origins.size());
    std::uint64_t faces = 0;
    std::fprintf(stderr, "meshing %zu chunks and their brute-force face sets ...\n", origins.size());
    std::vector<meshing::chunk_voxels> chunks(std::max(1u, o.threads));
    std::vector<std::vector<std::uint8_t>> scratch(chunks.size());
    std::vector<meshing::mesher> meshers(chunks.size(), meshing::mesher({.ambient_occlusion = true}));
    std::vector<std::uint64_t> chunk_faces(origins.size());
    parallel_for(origins.size(), unsigned(chunks.size()), [&](std::size_t i, unsigned w) {
        meshing::fill_chunk(model, origins[i], chunks[w], scratch[w]);
        meshers[w].mesh(chunks[w], meshes[i]);
        auto expected = check::brute_force_faces(chunks[w], true);
        chunk_faces[i] = expected.size();
        face_mismatches[i] = check::face_set_mismatches(expected, check::expand_quads(meshes[i]));
        order_problems[i] = !check::pop_order_problem(meshes[i]).empty();
    });
    std::uint64_t canonical = 0, order = 0;
    for (std::size_t i = 0; i < origins.size(); ++i) {
        faces += chunk_faces[i], canonical += face_mismatches[i], order += order_problems[i];
        if ((face_mismatches[i] || order_problems[i]) && canonical + order < 4)
            std::printf("  chunk (%d, %d, %d): %llu face mismatches; %s\n", origins[i].x, origins[i].y, origins[i].z,
                        (unsigned long long)face_mismatches[i], check::pop_order_problem(meshes[i]).c_str());
    }
    std::printf("canonical faces: %zu chunks, %llu faces: %llu mismatches; POP order: %llu chunks wrong\n", origins.size(),
                (unsigned long long)faces, (unsigned long long)canonical, (unsigned long long)order);

    std::uint64_t kernel = check_kernel(model, origins, meshes, o.kernel_chunks);

    std::uint64_t open = 0, coverage = 0;
    for (int level = 0; level < VX_MESH_LEVELS; ++level) open += check::open_lines(meshes, level);
    for (auto& m : meshes) {
        meshing::chunk_mesh squashed = m;
        meshing::remove_squashed_faces(squashed);
        order += !check::pop_order_problem(squashed, false).empty();
        for (int level = 1; level < VX_MESH_LEVELS; ++level) coverage += check::coverage_changes(m, squashed, level);
    }
    std::printf("closedness: %llu open axis lines over levels 0..%d; squashed-face pass: %llu cells changed\n",
                (unsigned long long)open, VX_MESH_LEVELS - 1, (unsigned long long)coverage);

    auto cases = check::find_morph_cases(meshes);
    std::size_t all_shared = cases.shared.size(), all_t = cases.t_junctions.size();
    keep_sample(cases.shared, 5000, o.seed);
    keep_sample(cases.t_junctions, 20000, o.seed + 1);
    auto morphs = check::check_morphs(meshes, cases, model.bounds(), o.views, o.seed);
    std::printf("morphing over %llu views: %zu of %zu shared vertices, %zu of %zu T-junctions: %llu split vertices, "
                "%llu T-vertices off their edge\n",
                (unsigned long long)morphs.views, cases.shared.size(), all_shared, cases.t_junctions.size(), all_t,
                (unsigned long long)morphs.split_vertices, (unsigned long long)morphs.t_vertices_off);
    std::uint64_t raster = check_raster(model, meshes, o.raster_views);
    return canonical + order + kernel + open + coverage + morphs.split_vertices + morphs.t_vertices_off + raster;
}

}  // namespace voxray::tool
