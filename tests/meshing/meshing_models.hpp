// Models for the mesher's tests: blobs of a few materials that merge into large quads and
// cross chunk sides, at negative coordinates too.
#pragma once
#include <cstdint>
#include <vector>

#include "voxray/core/box.hpp"
#include "voxray/meshing/chunk_source.hpp"
#include "voxray/meshing/mesher.hpp"
#include "voxray/meshing/squashed.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/scenes/noise.hpp"

namespace voxray::test {

// `count` boxes and balls of materials 1..materials inside `bounds`, with a sprinkle of
// single voxels (T-junctions and unit quads everywhere).
inline voxel_model blob_model(std::uint64_t seed, box3i bounds, int count = 12, int materials = 3) {
    voxel_model m;
    scenes::rng g{seed};
    glm::ivec3 e = bounds.extent();
    for (int i = 0; i < count; ++i) {
        glm::ivec3 c = bounds.min + glm::ivec3(g.range(0, e.x - 1), g.range(0, e.y - 1), g.range(0, e.z - 1));
        int r = g.range(2, 18);
        auto material = std::uint8_t(g.range(1, materials));
        bool ball = g.uniform() < 0.5;
        for (int z = -r; z <= r; ++z)
            for (int y = -r; y <= r; ++y)
                for (int x = -r; x <= r; ++x) {
                    glm::ivec3 p = c + glm::ivec3(x, y, z);
                    if (!bounds.contains(p)) continue;
                    if (ball && x * x + y * y + z * z > r * r) continue;
                    m.set(p, material);
                }
    }
    for (int i = 0; i < count * 40; ++i)
        m.set(bounds.min + glm::ivec3(g.range(0, e.x - 1), g.range(0, e.y - 1), g.range(0, e.z - 1)),
              std::uint8_t(g.range(0, materials)));
    return m;
}

// Every chunk of the model meshed (no AO), with the squashed-face pass where asked.
inline std::vector<meshing::chunk_mesh> mesh_all(const voxel_model& model, bool squashed = true) {
    std::vector<meshing::chunk_mesh> meshes;
    meshing::mesher mesher;
    meshing::chunk_voxels chunk;
    std::vector<std::uint8_t> scratch;
    for (glm::ivec3 origin : meshing::chunk_origins(model)) {
        meshing::fill_chunk(model, origin, chunk, scratch);
        mesher.mesh(chunk, meshes.emplace_back());
        if (squashed) meshing::remove_squashed_faces(meshes.back());
    }
    return meshes;
}

}  // namespace voxray::test
