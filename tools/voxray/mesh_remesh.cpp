#include "mesh_remesh.hpp"

#include <chrono>
#include <variant>
#include <vector>

#include "timing.hpp"
#include "voxray/brickmap/read_box.hpp"
#include "voxray/check/random_edits.hpp"
#include "voxray/meshing/remesh.hpp"
#include "voxray/naadf/read_box.hpp"

namespace voxray::tool {

namespace {

template <class Structure>
nlohmann::json remesh_one(const voxel_model& model, int rounds) {
    Structure structure(model);
    auto origins = meshing::chunk_origins(model);
    // Reading alone: each chunk's box and shell through the structure's read_box.
    std::vector<double> read_us;
    meshing::chunk_voxels chunk;
    std::vector<std::uint8_t> scratch;
    for (glm::ivec3 origin : origins) {
        auto start = std::chrono::steady_clock::now();
        meshing::fill_chunk(structure, origin, chunk, scratch);
        read_us.push_back(seconds_since(start) * 1e6);
    }
    meshing::chunk_meshes kept;
    kept.mesh(structure, origins);
    box3i area = model.bounds();
    std::vector<double> us_per_chunk, edit_us;
    std::size_t chunks = 0;
    for (int round = 0; round < rounds; ++round) {
        std::vector<box3i> edited;
        auto start = std::chrono::steady_clock::now();
        for (const region_edit& e : random_edits(area, 1, 900 + std::uint64_t(round)))
            std::visit(
                [&](const auto& region) {
                    structure.apply(region, e.op, std::uint8_t(e.value));
                    edited.push_back(region.bounds());
                },
                e.region);
        edit_us.push_back(seconds_since(start) * 1e6);
        meshing::remesh_stats stats = kept.remesh(structure, edited);
        chunks += stats.chunks;
        if (stats.chunks) us_per_chunk.push_back(stats.microseconds_per_chunk());
    }
    return {{"read_us_median", percentile(read_us, 0.5)},
            {"remesh_us_per_chunk_median", percentile(us_per_chunk, 0.5)},
            {"chunks_per_edit", rounds ? double(chunks) / rounds : 0.0},
            {"edit_us_median", percentile(edit_us, 0.5)},
            {"edits", rounds}};
}

}  // namespace

nlohmann::json remesh_figures(const voxel_model& model, int rounds) {
    if (model.voxel_count() == 0) return nlohmann::json::object();
    return {{"brickmap", remesh_one<brickmap<>>(model, rounds)}, {"naadf", remesh_one<naadf>(model, rounds)}};
}

}  // namespace voxray::tool
