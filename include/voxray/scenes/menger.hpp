// The Menger sponge: a cube cut into 3x3x3 sub-cubes, the centre and the six
// face centres removed, recursively. A voxel is solid iff at no level two or
// more of its base-3 digits are 1:
//
//   level 1 (3^3 cells), slice z = 1:   # . #      '#' solid, '.' removed
//                                       . . .
//                                       # . #
//
// 20^level solid cells; each cell is `cell`^3 voxels. Self-similar and full of
// repeated subtrees, it stresses deduplicating structures (SVDAG) and gives
// long, exact empty-space skips (level-k holes are 3^k cells wide).
#pragma once
#include <cstdint>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/scenes/parallel_fill.hpp"

namespace voxray::scenes {

struct menger_options {
    int level = 5;         // 1..7
    int cell = 2;          // voxels per edge of a level-0 cube, 1..8
    unsigned threads = 0;  // 0: all hardware threads
};

// Above this many voxels the sponge is refused (memory: ~4 KiB per 16^3 chunk).
inline constexpr std::uint64_t menger_max_voxels = std::uint64_t(1) << 28;

inline std::uint64_t menger_voxel_count(int level, int cell) {
    std::uint64_t n = std::uint64_t(cell) * cell * cell;
    for (int i = 0; i < level; ++i) n *= 20;
    return n;
}

// Model: [0, cell * 3^level)^3, Z up, two colours alternating by the level-1
// sub-cube so the recursion stays visible in renders.
inline voxel_model make_menger(const menger_options& opt = {}) {
    if (opt.level < 1 || opt.level > 7) fail("menger level ", opt.level, " is outside 1..7");
    if (opt.cell < 1 || opt.cell > 8) fail("menger cell size ", opt.cell, " is outside 1..8");
    check_limit("menger voxel count", menger_voxel_count(opt.level, opt.cell), menger_max_voxels);
    int cells = 1;
    for (int i = 0; i < opt.level; ++i) cells *= 3;
    const int size = cells * opt.cell;

    // Per coordinate, a bit per level whose digit is 1; a cell is removed iff two
    // of its three masks share a bit. The top digit (0..2) is kept for colour.
    std::vector<std::uint8_t> ones(std::size_t(size), 0);
    std::vector<std::uint8_t> top(std::size_t(size), 0);
    for (int x = 0; x < size; ++x) {
        int c = x / opt.cell;
        std::uint8_t m = 0;
        for (int l = 0; l < opt.level; ++l, c /= 3) m |= std::uint8_t((c % 3 == 1) << l);
        ones[std::size_t(x)] = m;
        top[std::size_t(x)] = std::uint8_t((x / opt.cell) * 3 / cells);  // top digit 0..2
    }

    voxel_model model;
    model.up_axis = 2;
    auto& pal = model.palette();
    pal[1].colour = {214, 180, 118, 255};  // warm sandstone
    pal[2].colour = {168, 122, 84, 255};   // darker clay
    pal[3].colour = {226, 214, 190, 255};  // pale stone, edges of the top level

    std::vector<chunk_column_job> jobs;
    int chunks = (size + voxel_model::chunk_edge - 1) / voxel_model::chunk_edge;
    for (int cy = 0; cy < chunks; ++cy)
        for (int cx = 0; cx < chunks; ++cx) jobs.push_back({cx, cy, 0, chunks - 1});
    build_chunks(model, jobs, opt.threads, [&](glm::ivec3 cc, voxel_model::chunk& c) {
        glm::ivec3 o = cc * voxel_model::chunk_edge;
        for (int lz = 0; lz < voxel_model::chunk_edge; ++lz) {
            int z = o.z + lz;
            if (z >= size) break;
            for (int ly = 0; ly < voxel_model::chunk_edge; ++ly) {
                int y = o.y + ly;
                if (y >= size) break;
                std::uint8_t mz = ones[std::size_t(z)], my = ones[std::size_t(y)], myz = mz & my, oyz = mz | my;
                int tyz = top[std::size_t(y)] + top[std::size_t(z)];
                for (int lx = 0; lx < voxel_model::chunk_edge; ++lx) {
                    int x = o.x + lx;
                    if (x >= size) break;
                    std::uint8_t mx = ones[std::size_t(x)];
                    if (myz | (mx & oyz)) continue;
                    int t = tyz + top[std::size_t(x)];  // 0..6; odd/even checkerboard of the top level
                    std::uint8_t v = (t % 2) ? 2 : 1;
                    if (t == 0 || t == 6) v = 3;  // the two opposite corner cubes
                    c.voxels[std::size_t(voxel_model::local_index({lx, ly, lz}))] = v;
                }
            }
        }
    });
    return model;
}

}  // namespace voxray::scenes
