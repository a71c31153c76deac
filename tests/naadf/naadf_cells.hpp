// Test-side decoding of NAADF blobs with the layout's arithmetic only (not the host
// type's code): the cell holding a voxel, its cuboid, and the check every test of
// builds and edits makes (cells match the model, every cuboid is empty).
#pragma once
#include <gtest/gtest.h>

#include <span>
#include <string>
#include <vector>

#include <glm/vector_relational.hpp>

#include "voxray/model/voxel_model.hpp"
#include "voxray/naadf/layout.h"

namespace voxray::test {

// The cell holding world voxel p, decoded from the blob with the layout's arithmetic.
struct decoded_cell {
    std::uint32_t value;
    int level;  // log2 of the edge: 8, 4, 2, 0
    bool solid;
};

inline decoded_cell cell_at(std::span<const std::uint32_t> w, glm::ivec3 p) {
    glm::ivec3 origin, shift, pages;
    for (int a = 0; a < 3; ++a) {
        origin[a] = int(w[VX_NA_HEADER_ORIGIN + a]);
        shift[a] = int(w[VX_NA_HEADER_SHIFT + a]);
        pages[a] = int(w[VX_NA_HEADER_PAGES_DIM + a]);
    }
    auto g = glm::uvec3(p - origin + shift);
    std::uint32_t cell = w[w[VX_NA_HEADER_PAGE_TABLE] + VX_NA_PAGE_SLOT(g.x, g.y, g.z, std::uint32_t(pages.x),
                                                                        std::uint32_t(pages.x * pages.y))];
    if (VX_NA_STATE(cell) != VX_NA_MIXED) return {cell, 8, VX_NA_STATE(cell) == VX_NA_UNIFORM};
    cell = w[w[VX_NA_HEADER_CHUNKS] + VX_NA_PAYLOAD(cell) * VX_NA_CHUNK_ARRAY_WORDS + VX_NA_CHUNK_INDEX(g.x, g.y, g.z)];
    if (VX_NA_STATE(cell) != VX_NA_MIXED) return {cell, 4, VX_NA_STATE(cell) == VX_NA_UNIFORM};
    cell = w[w[VX_NA_HEADER_BLOCKS] + VX_NA_PAYLOAD(cell) * VX_NA_BLOCK_ARRAY_WORDS + VX_NA_BLOCK_INDEX(g.x, g.y, g.z)];
    if (VX_NA_STATE(cell) != VX_NA_MIXED) return {cell, 2, VX_NA_STATE(cell) == VX_NA_UNIFORM};
    std::uint32_t i = VX_NA_VOXEL_INDEX(g.x, g.y, g.z);
    std::uint32_t v = (w[w[VX_NA_HEADER_VOXELS] + VX_NA_PAYLOAD(cell) * VX_NA_GROUP_WORDS + VX_NA_VOXEL_WORD(i)] >>
                       VX_NA_VOXEL_SHIFT(i)) & 0xFFFFu;
    return {v, 0, (v & VX_NA_VOXEL_SOLID) != 0};
}

// The empty cuboid an empty cell's AADF describes, in world voxels.
inline box3i cuboid_of(std::span<const std::uint32_t> w, glm::ivec3 p, const decoded_cell& c) {
    glm::ivec3 origin, shift;
    for (int a = 0; a < 3; ++a) origin[a] = int(w[VX_NA_HEADER_ORIGIN + a]), shift[a] = int(w[VX_NA_HEADER_SHIFT + a]);
    unsigned k = c.level >= VX_NA_CHUNK_BITS ? 5 : 2;
    int size = 1 << c.level;
    glm::ivec3 g = p - origin + shift, cell_min = (g / size) * size - shift + origin;  // g >= 0 here
    box3i b;
    for (int a = 0; a < 3; ++a) {
        b.min[a] = cell_min[a] - int(VX_NA_AADF_FIELD(c.value, 2 * a + 1, k)) * size;
        b.max[a] = cell_min[a] + size + int(VX_NA_AADF_FIELD(c.value, 2 * a, k)) * size;
    }
    return b;
}

// Solid-voxel counts of every box of `world`, from a summed-volume table of the model.
class solid_counts {
public:
    solid_counts(const voxel_model& m, const box3i& world) : world_(world), n_(world.extent() + 1) {
        sums_.assign(std::size_t(n_.x) * n_.y * n_.z, 0);
        for (int z = 1; z < n_.z; ++z)
            for (int y = 1; y < n_.y; ++y)
                for (int x = 1; x < n_.x; ++x)
                    at(x, y, z) = (m.get(world.min + glm::ivec3(x - 1, y - 1, z - 1)) ? 1 : 0) + at(x - 1, y, z) +
                                  at(x, y - 1, z) + at(x, y, z - 1) - at(x - 1, y - 1, z) - at(x - 1, y, z - 1) -
                                  at(x, y - 1, z - 1) + at(x - 1, y - 1, z - 1);
    }
    // Solid voxels of the model inside b (outside `world` there are none).
    std::int64_t in(box3i b) const {
        glm::ivec3 lo = glm::clamp(b.min - world_.min, glm::ivec3(0), n_ - 1);
        glm::ivec3 hi = glm::clamp(b.max - world_.min, glm::ivec3(0), n_ - 1);
        if (glm::any(glm::lessThanEqual(hi, lo))) return 0;
        return at(hi.x, hi.y, hi.z) - at(lo.x, hi.y, hi.z) - at(hi.x, lo.y, hi.z) - at(hi.x, hi.y, lo.z) +
               at(lo.x, lo.y, hi.z) + at(lo.x, hi.y, lo.z) + at(hi.x, lo.y, lo.z) - at(lo.x, lo.y, lo.z);
    }

private:
    std::int64_t& at(int x, int y, int z) { return sums_[(std::size_t(z) * n_.y + y) * n_.x + x]; }
    std::int64_t at(int x, int y, int z) const { return sums_[(std::size_t(z) * n_.y + y) * n_.x + x]; }
    box3i world_;
    glm::ivec3 n_;
    std::vector<std::int64_t> sums_;
};

// Every voxel of `world` (which holds all of the model's voxels): the blob's cell agrees
// with the model, and an empty cell's cuboid holds the voxel and no solid voxel.
inline void expect_cells_match(std::span<const std::uint32_t> w, const voxel_model& m, const box3i& world,
                               const std::string& what) {
    solid_counts counts(m, world);
    for (int z = world.min.z; z < world.max.z; ++z)
        for (int y = world.min.y; y < world.max.y; ++y)
            for (int x = world.min.x; x < world.max.x; ++x) {
                glm::ivec3 p{x, y, z};
                decoded_cell c = cell_at(w, p);
                std::uint8_t material = m.get(p);
                ASSERT_EQ(c.solid, material != 0) << what << ": voxel " << x << " " << y << " " << z;
                if (c.solid) {
                    ASSERT_EQ(c.value & VX_NA_TYPE_MASK, material) << what << ": voxel " << x << " " << y << " " << z;
                    continue;
                }
                box3i b = cuboid_of(w, p, c);
                ASSERT_TRUE(b.contains(p)) << what;
                ASSERT_EQ(counts.in(b), 0) << what << ": the cuboid of " << x << " " << y << " " << z << " (level "
                                           << c.level << ") holds solid voxels";
            }
}

}  // namespace voxray::test
