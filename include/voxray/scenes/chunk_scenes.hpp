// One-chunk scenes (64^3, origin 0) for the mesher's benchmarks and tests: the anchors of
// the blocky-meshing literature and the two extremes.
//
//   sphere30    a ball of radius 30 about the chunk's centre, one material
//   checker     a 3-D checkerboard: every voxel with x + y + z even, one material (the worst
//               case for merging: no two faces merge)
//   noise50     each voxel solid with probability 1/2, 4 materials (seeded hash)
//   terrain64   a heightmap of fractal value noise, heights 8..56, Z up, filled to the
//               ground, 4 materials by depth and height
#pragma once
#include <cmath>
#include <cstdint>
#include <string_view>

#include "voxray/model/voxel_model.hpp"
#include "voxray/scenes/noise.hpp"

namespace voxray::scenes {

inline bool is_chunk_scene(std::string_view name) {
    return name == "sphere30" || name == "checker" || name == "noise50" || name == "terrain64";
}

inline voxel_model make_chunk_scene(std::string_view name) {
    constexpr int n = 64;
    constexpr std::uint64_t seed = 1;
    voxel_model model;
    auto fill = [&](auto material_at) {
        for (int cz = 0; cz < n; cz += voxel_model::chunk_edge)
            for (int cy = 0; cy < n; cy += voxel_model::chunk_edge)
                for (int cx = 0; cx < n; cx += voxel_model::chunk_edge) {
                    auto c = std::make_unique<voxel_model::chunk>();
                    for (int i = 0; i < voxel_model::chunk_voxels; ++i) {
                        glm::ivec3 p = glm::ivec3(cx, cy, cz) + voxel_model::local_position(i);
                        c->voxels[i] = material_at(p);
                    }
                    model.replace_chunk(glm::ivec3(cx, cy, cz) / voxel_model::chunk_edge, std::move(c));
                }
    };
    if (name == "sphere30") {
        fill([](glm::ivec3 p) -> std::uint8_t {
            glm::dvec3 d = glm::dvec3(p) + 0.5 - double(n / 2);
            return d.x * d.x + d.y * d.y + d.z * d.z < 30.0 * 30.0;
        });
    } else if (name == "checker") {
        fill([](glm::ivec3 p) -> std::uint8_t { return ((p.x + p.y + p.z) & 1) == 0; });
    } else if (name == "noise50") {
        fill([](glm::ivec3 p) -> std::uint8_t {
            std::uint64_t h = hash(seed, 50, p.x, p.y, p.z);
            return (h & 1) ? std::uint8_t(1 + ((h >> 1) & 3)) : 0;
        });
    } else if (name == "terrain64") {
        fill([](glm::ivec3 p) -> std::uint8_t {
            int ground = 8 + int(48.0 * fbm(seed, 64, p.x / 24.0, p.y / 24.0, 4));
            if (p.z > ground) return 0;
            if (p.z < ground - 3) return 3;        // rock
            if (p.z < ground) return 2;            // dirt
            return ground > 40 ? 4 : 1;            // snow or grass on top
        });
    } else {
        fail("unknown one-chunk scene '", name, "' (sphere30, checker, noise50, terrain64)");
    }
    return model;
}

}  // namespace voxray::scenes
