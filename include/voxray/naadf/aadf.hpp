// Axis-aligned distance fields (paper section 3.3): for an empty cell, how far an empty
// cuboid around it reaches in each of the six directions, in cells of its own layer, each
// at most `limit` and never past the grid it lies in (the cell of the layer above).
//
// The cuboid grows in a fixed order, one cell per direction per round (x, then y, then z;
// + before -), as the paper's synchronised iterations do; a direction stops at the first
// slab that holds a solid cell. Whether a slab is empty is one lookup: a bit mask for the
// 4^3 grids of voxels and blocks, a summed-volume table for the bigger ones. So the cost
// is O(cells x limit), linear in the number of cells like the paper's neighbour merging,
// and a cell's field depends only on the content of the grid it lies in.
#pragma once
#include <array>
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
// whether the half-open box [lo, hi) holds no solid cell.
template <class BoxEmpty>
aadf6 grow_cuboid(glm::ivec3 cell, glm::ivec3 n, unsigned limit, BoxEmpty&& box_empty) {
    glm::ivec3 lo = cell, hi = cell + 1;
    aadf6 d{};
    std::array<bool, 6> open{true, true, true, true, true, true};
    for (bool grew = true; grew;) {
        grew = false;
        for (int axis = 0; axis < 3; ++axis) {
            for (int side = 0; side < 2; ++side) {
                int dir = 2 * axis + side;
                if (!open[dir]) continue;
                bool room = d[dir] < limit && (side == 0 ? hi[axis] < n[axis] : lo[axis] > 0);
                glm::ivec3 slab_lo = lo, slab_hi = hi;
                if (side == 0) slab_lo[axis] = hi[axis], slab_hi[axis] = hi[axis] + 1;
                else slab_lo[axis] = lo[axis] - 1, slab_hi[axis] = lo[axis];
                if (!room || !box_empty(slab_lo, slab_hi)) {
                    open[dir] = false;
                    continue;
                }
                (side == 0 ? hi[axis] : lo[axis]) += side == 0 ? 1 : -1;
                ++d[dir];
                grew = true;
            }
        }
    }
    return d;
}

// A 4^3 grid as a 64-bit mask (bit x | y << 2 | z << 4, the layout's voxel and block
// index), and the mask of every box in it, so a slab test is one AND.
class grid4_boxes {
public:
    grid4_boxes() {
        for (int x0 = 0; x0 < 4; ++x0)
            for (int x1 = x0 + 1; x1 <= 4; ++x1)
                for (int y0 = 0; y0 < 4; ++y0)
                    for (int y1 = y0 + 1; y1 <= 4; ++y1)
                        for (int z0 = 0; z0 < 4; ++z0)
                            for (int z1 = z0 + 1; z1 <= 4; ++z1) {
                                std::uint64_t m = 0;
                                for (int z = z0; z < z1; ++z)
                                    for (int y = y0; y < y1; ++y)
                                        for (int x = x0; x < x1; ++x) m |= std::uint64_t(1) << VX_NA_VOXEL_INDEX(x, y, z);
                                masks_[slot({x0, y0, z0}, {x1, y1, z1})] = m;
                            }
    }
    std::uint64_t mask(glm::ivec3 lo, glm::ivec3 hi) const { return masks_[slot(lo, hi)]; }

    static const grid4_boxes& get() {
        static const grid4_boxes boxes;
        return boxes;
    }

private:
    static int slot(glm::ivec3 lo, glm::ivec3 hi) { return ((lo.x * 5 + hi.x) * 25 + (lo.y * 5 + hi.y)) * 25 + lo.z * 5 + hi.z; }
    std::array<std::uint64_t, 25 * 25 * 25> masks_{};
};

// The packed AADFs (k bits a field, limit 3) of the 64 cells of a 4^3 grid whose solid
// cells are the set bits of `solid`; solid cells get 0.
inline std::array<std::uint32_t, 64> grid4_aadfs(std::uint64_t solid, unsigned k) {
    const auto& boxes = grid4_boxes::get();
    std::array<std::uint32_t, 64> out{};
    auto box_empty = [&](glm::ivec3 lo, glm::ivec3 hi) { return (solid & boxes.mask(lo, hi)) == 0; };
    for (int i = 0; i < 64; ++i) {
        if ((solid >> i) & 1u) continue;
        glm::ivec3 cell{i & 3, (i >> 2) & 3, i >> 4};
        out[i] = pack_aadf(grow_cuboid(cell, glm::ivec3(4), 3, box_empty), k);
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
    bool empty(glm::ivec3 lo, glm::ivec3 hi) const {
        std::uint32_t c = at(hi.x, hi.y, hi.z) - at(lo.x, hi.y, hi.z) - at(hi.x, lo.y, hi.z) - at(hi.x, hi.y, lo.z) +
                          at(lo.x, lo.y, hi.z) + at(lo.x, hi.y, lo.z) + at(hi.x, lo.y, lo.z) - at(lo.x, lo.y, lo.z);
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
    auto box_empty = [&](glm::ivec3 lo, glm::ivec3 hi) { return counts.empty(lo, hi); };
    std::size_t i = 0;
    for (int z = 0; z < n.z; ++z)
        for (int y = 0; y < n.y; ++y)
            for (int x = 0; x < n.x; ++x, ++i)
                if (!solid[i]) out[i] = pack_aadf(grow_cuboid({x, y, z}, n, limit, box_empty), k);
    return out;
}

}  // namespace voxray::naadf_detail
