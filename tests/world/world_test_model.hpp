// The model the world tests share: a terrain plus a block of noise at negative coordinates,
// so that chunks, LODs and the grid's origin all meet negative cells; the build options
// they use for it, and the cuts they show.
#pragma once
#include "random_models.hpp"
#include "voxray/scenes/builtin.hpp"
#include "voxray/world/build/world_build.hpp"
#include "voxray/world/world.hpp"

namespace voxray::test {

inline voxel_model world_test_model() {
    voxel_model model = scenes::make_builtin("terrain:120", 2);
    voxel_model noise = random_model(40, 0.05f, 3, glm::ivec3(-50, -20, 30));
    noise.for_each_voxel([&](glm::ivec3 p, std::uint8_t v) { model.set(p, v); });
    return model;
}

// Builds of the test model: chunks of 16^3, so that it spans many chunks and LODs.
inline world_build_options small_chunks(unsigned threads = 2) {
    world_build_options o;
    o.chunk_bits = 4;
    o.threads = threads;
    return o;
}

// Every chunk of one LOD.
inline std::vector<placement> uniform_cut(const chunked_world& w, int lod) {
    std::vector<placement> cut;
    glm::ivec3 n = (w.grid().cells + (1 << lod) - 1) >> lod;
    for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
            for (int x = 0; x < n.x; ++x)
                if (const chunk_record* c = w.find({lod, {x, y, z}})) cut.push_back({c->key, c});
    return cut;
}

// The coarsest LOD everywhere; LOD 1 over the lower half in x; LOD 0 in every cell whose
// x + y + z is even within it: coarse chunks split around finer ones, cells next to cells
// of other LODs everywhere.
inline std::vector<placement> split_cut(const chunked_world& w) {
    int top = w.grid().top_lod;
    auto cut = uniform_cut(w, top);
    int half = w.grid().cells.x / 2;
    for (auto& p : uniform_cut(w, 1))
        if ((p.key.cell.x << 1) < half) cut.push_back(p);
    for (auto& p : uniform_cut(w, 0))
        if (p.key.cell.x < half && (p.key.cell.x + p.key.cell.y + p.key.cell.z) % 2 == 0) cut.push_back(p);
    return cut;
}

}  // namespace voxray::test
