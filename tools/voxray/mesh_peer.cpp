#include "mesh_peer.hpp"

#include <chrono>

#include <meshoptimizer.h>

#include "mesh_raster.hpp"
#include "voxray/meshing/quad_corners.hpp"

namespace voxray::tool {

namespace {

// A chunk's quads drawn at level 0 as indexed triangles, corners that coincide welded into
// one vertex (what a simplifier needs to collapse edges).
struct indexed_mesh {
    std::vector<float> positions;  // 3 per vertex
    std::vector<unsigned> indices;
};

indexed_mesh level_zero(const meshing::chunk_mesh& m) {
    std::vector<float> corners;
    std::vector<unsigned> indices;
    meshing::for_each_quad_at(m, 0, [&](std::uint32_t, const std::array<glm::ivec3, 4>& quad) {
        unsigned base = unsigned(corners.size() / 3);
        for (const glm::ivec3& p : quad) corners.insert(corners.end(), {float(p.x), float(p.y), float(p.z)});
        indices.insert(indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
    });
    std::vector<unsigned> remap(corners.size() / 3);
    std::size_t vertices = meshopt_generateVertexRemap(remap.data(), indices.data(), indices.size(), corners.data(),
                                                       corners.size() / 3, 3 * sizeof(float));
    indexed_mesh out;
    out.positions.resize(vertices * 3);
    out.indices.resize(indices.size());
    meshopt_remapVertexBuffer(out.positions.data(), corners.data(), corners.size() / 3, 3 * sizeof(float), remap.data());
    meshopt_remapIndexBuffer(out.indices.data(), indices.data(), indices.size(), remap.data());
    return out;
}

// Every chunk's simplified triangles as one mesh over all chunks' vertices (for a picture).
struct joined_mesh {
    std::vector<float> positions;
    std::vector<std::uint32_t> indices;
    void add(const indexed_mesh& chunk, const std::vector<unsigned>& chunk_indices, std::size_t count) {
        auto base = std::uint32_t(positions.size() / 3);
        positions.insert(positions.end(), chunk.positions.begin(), chunk.positions.end());
        for (std::size_t i = 0; i < count; ++i) indices.push_back(base + chunk_indices[i]);
    }
};

}  // namespace

nlohmann::json meshoptimizer_levels(const std::vector<meshing::chunk_mesh>& meshes, int up_axis) {
    nlohmann::json levels = nlohmann::json::array();
    std::vector<indexed_mesh> inputs;
    for (auto& m : meshes) inputs.push_back(level_zero(m));
    level_images images(meshes, up_axis);
    for (int level = 1; level < VX_MESH_LEVELS; ++level) {
        std::uint64_t target = 0, reached = 0, reached_sloppy = 0;
        double seconds = 0, seconds_sloppy = 0, worst_error = 0, worst_error_sloppy = 0;
        joined_mesh simplified, sloppy;
        for (std::size_t c = 0; c < meshes.size(); ++c) {
            const auto& in = inputs[c];
            std::size_t target_indices = std::size_t(meshes[c].drawn(level)) * 6;
            std::vector<unsigned> out(in.indices.size());
            float error = 0;
            auto start = std::chrono::steady_clock::now();
            std::size_t got = meshopt_simplify(out.data(), in.indices.data(), in.indices.size(), in.positions.data(),
                                               in.positions.size() / 3, 3 * sizeof(float), target_indices, 1.0f, 0, &error);
            seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            target += target_indices / 3, reached += got / 3;
            worst_error = std::max(worst_error, double(error));
            simplified.add(in, out, got);
            start = std::chrono::steady_clock::now();
            got = meshopt_simplifySloppy(out.data(), in.indices.data(), in.indices.size(), in.positions.data(),
                                         in.positions.size() / 3, 3 * sizeof(float), target_indices, 1.0f, &error);
            seconds_sloppy += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            reached_sloppy += got / 3;
            worst_error_sloppy = std::max(worst_error_sloppy, double(error));
            sloppy.add(in, out, got);
        }
        nlohmann::json row = {{"level", level}, {"target_triangles", target}, {"triangles", reached},
                              {"ms", seconds * 1e3}, {"error", worst_error}, {"sloppy_triangles", reached_sloppy},
                              {"sloppy_ms", seconds_sloppy * 1e3}, {"sloppy_error", worst_error_sloppy}};
        if (images.available()) {
            row["pop_image_rmse"] = images.pop_rmse(level);
            row["image_rmse"] = images.triangles_rmse(simplified.positions, simplified.indices);
            row["sloppy_image_rmse"] = images.triangles_rmse(sloppy.positions, sloppy.indices);
        }
        levels.push_back(row);
    }
    return levels;
}

}  // namespace voxray::tool
