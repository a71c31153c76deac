// Axis-aligned distance fields (paper section 3.3): for an empty cell, how far an empty
// cuboid around it reaches in each of the six directions, in cells of its own layer, each
// at most `limit` and never past the grid it lies in (the cell of the layer above).
//
// The cuboid grows in a fixed order, one cell per direction per round (x, then y, then z;
// + before -), as the paper's synchronised iterations do; a direction stops at the first
// slab that holds a solid cell. Whether a slab is empty is one lookup: bit masks for the
// 4^3 grids of voxels and blocks, a summed-volume table for the bigger ones. So the cost
// is O(cells x limit), linear in the number of cells like the paper's neighbour merging,
// and a cell's field depends only on the content of the grid it lies in.
#pragma once
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "voxray/naadf/layout.h"

namespace voxray::naadf_detail {

// +x -x +y -y +z -z, as the layout's fields.
using aadf6 = std::array<std::uint32_t, 6>;

// Packs six fields of k bits each (layout.h: +x lowest).
inline std::uint32_t pack_aadf(const aadf6& d, unsigned k) {
    std::uint32_t word = 0;
    for (unsigned dir = 0; dir < 6; ++dir) word |= VX_NA_AADF_PUT(d[dir], dir, k);
    return word;
}

// Grows the cuboid of empty cell `cell` in a grid of `n` cells; box_empty(lo, hi) says
// whether the half-open box [lo, hi) (int[3] each) holds no solid cell.
template <class BoxEmpty>
aadf6 grow_cuboid(glm::ivec3 cell, glm::ivec3 n, unsigned limit, BoxEmpty&& box_empty) {
    int lo[3] = {cell.x, cell.y, cell.z}, hi[3] = {cell.x + 1, cell.y + 1, cell.z + 1};
    aadf6 d{};
    unsigned open = 0x3F;  // bit 2 * axis + side (side 0: +, 1: -)
    // Each round, every open direction grows by one cell or closes for good; growth is
    // bounded by `limit` and the grid, so the loop ends.
    while (open) {
        for (int axis = 0; axis < 3; ++axis)
            for (int side = 0; side < 2; ++side) {
                int dir = 2 * axis + side;
                if (!(open >> dir & 1u)) continue;
                bool room = d[dir] < limit && (side == 0 ? hi[axis] < n[axis] : lo[axis] > 0);
                int slab_lo[3] = {lo[0], lo[1], lo[2]}, slab_hi[3] = {hi[0], hi[1], hi[2]};
                if (side == 0) slab_lo[axis] = hi[axis], slab_hi[axis] = hi[axis] + 1;
                else slab_lo[axis] = lo[axis] - 1, slab_hi[axis] = lo[axis];
                if (!room || !box_empty(slab_lo, slab_hi)) {
                    open &= ~(1u << dir);
                    continue;
                }
                if (side == 0) ++hi[axis];
                else --lo[axis];
                ++d[dir];
            }
    }
    return d;
}

// A 4^3 grid as a 64-bit mask (bit x | y << 2 | z << 4, the layout's voxel and block
// index). A box's mask is the AND of three range masks, one per axis, from tables small
// enough to stay in L1: a slab test is a few ANDs.
class grid4_ranges {
public:
    grid4_ranges() {
        for (int lo = 0; lo < 4; ++lo)
            for (int hi = lo + 1; hi <= 4; ++hi)
                for (int i = 0; i < 64; ++i) {
                    glm::ivec3 c{i & 3, (i >> 2) & 3, i >> 4};
                    for (int a = 0; a < 3; ++a)
                        if (c[a] >= lo && c[a] < hi) range_[a][lo * 5 + hi] |= std::uint64_t(1) << i;
                }
    }
    // The cells whose coordinate on `axis` lies in [lo, hi).
    std::uint64_t range(int axis, int lo, int hi) const { return range_[axis][lo * 5 + hi]; }
    static const grid4_ranges& get() {
        static const grid4_ranges ranges;
        return ranges;
    }

private:
    std::array<std::array<std::uint64_t, 25>, 3> range_{};
};

// The packed AADFs (k bits a field, limit 3) of the 64 cells of a 4^3 grid whose solid
// cells are the set bits of `solid`; solid cells get 0. The same growth as grow_cuboid
// (tests check it), unrolled for this grid: three rounds reach every face of a 4-wide grid.
inline std::array<std::uint32_t, 64> grid4_aadfs(std::uint64_t solid, unsigned k) {
    const auto& ranges = grid4_ranges::get();
    std::array<std::uint32_t, 64> out{};
    for (std::uint64_t empty = ~solid; empty; empty &= empty - 1) {
        int i = std::countr_zero(empty);
        int lo[3] = {i & 3, (i >> 2) & 3, i >> 4};
        int hi[3] = {lo[0] + 1, lo[1] + 1, lo[2] + 1};
        std::uint64_t range[3] = {ranges.range(0, lo[0], hi[0]), ranges.range(1, lo[1], hi[1]), ranges.range(2, lo[2], hi[2])};
        unsigned open = 0x3F;  // bit 2 * axis + side
        for (int round = 0; round < 3 && open; ++round)
            for (int a = 0; a < 3; ++a) {
                std::uint64_t across = solid & range[(a + 1) % 3] & range[(a + 2) % 3];
                unsigned plus = 1u << (2 * a), minus = plus << 1;
                if ((open & plus) && (hi[a] == 4 || (across & ranges.range(a, hi[a], hi[a] + 1)))) open &= ~plus;
                if (open & plus) range[a] = ranges.range(a, lo[a], ++hi[a]);
                if ((open & minus) && (lo[a] == 0 || (across & ranges.range(a, lo[a] - 1, lo[a])))) open &= ~minus;
                if (open & minus) range[a] = ranges.range(a, --lo[a], hi[a]);
            }
        aadf6 d{};
        int cell[3] = {i & 3, (i >> 2) & 3, i >> 4};
        for (int a = 0; a < 3; ++a) d[2 * a] = std::uint32_t(hi[a] - cell[a] - 1), d[2 * a + 1] = std::uint32_t(cell[a] - lo[a]);
        out[i] = pack_aadf(d, k);
    }
    return out;
}

// Solid-cell counts of every box of a grid (x fastest), from a summed-volume table.
class box_counts {
public:
    box_counts(glm::ivec3 n, const std::vector<std::uint8_t>& solid) : n_(n), s_(std::size_t(n.x + 1) * (n.y + 1) * (n.z + 1), 0) {
        for (int z = 0; z < n.z; ++z)
            for (int y = 0; y < n.y; ++y)
                for (int x = 0; x < n.x; ++x) {
                    std::uint32_t v = solid[(std::size_t(z) * n.y + y) * n.x + x] ? 1u : 0u;
                    at(x + 1, y + 1, z + 1) = v + at(x, y + 1, z + 1) + at(x + 1, y, z + 1) + at(x + 1, y + 1, z) -
                                              at(x, y, z + 1) - at(x, y + 1, z) - at(x + 1, y, z) + at(x, y, z);
                }
    }
    bool empty(const int lo[3], const int hi[3]) const {
        std::uint32_t c = at(hi[0], hi[1], hi[2]) - at(lo[0], hi[1], hi[2]) - at(hi[0], lo[1], hi[2]) -
                          at(hi[0], hi[1], lo[2]) + at(lo[0], lo[1], hi[2]) + at(lo[0], hi[1], lo[2]) +
                          at(hi[0], lo[1], lo[2]) - at(lo[0], lo[1], lo[2]);
        return c == 0;
    }

private:
    std::uint32_t& at(int x, int y, int z) { return s_[(std::size_t(z) * (n_.y + 1) + y) * (n_.x + 1) + x]; }
    std::uint32_t at(int x, int y, int z) const { return s_[(std::size_t(z) * (n_.y + 1) + y) * (n_.x + 1) + x]; }
    glm::ivec3 n_;
    std::vector<std::uint32_t> s_;  // unsigned wrap-around keeps the inclusion-exclusion exact
};

// The packed AADFs (k bits a field, at most `limit`) of every cell of a grid of `n` cells
// (x fastest); solid cells get 0.
inline std::vector<std::uint32_t> grid_aadfs(glm::ivec3 n, const std::vector<std::uint8_t>& solid, unsigned limit,
                                             unsigned k) {
    box_counts counts(n, solid);
    std::vector<std::uint32_t> out(solid.size(), 0u);
    auto box_empty = [&](const int* lo, const int* hi) { return counts.empty(lo, hi); };
    std::size_t i = 0;
    for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
            for (int x = 0; x < n.x; ++x, ++i)
                if (!solid[i]) out[i] = pack_aadf(grow_cuboid({x, y, z}, n, limit, box_empty), k);
    return out;
}

}  // namespace voxray::naadf_detail
