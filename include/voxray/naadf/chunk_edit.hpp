// What an edit does to one NAADF chunk decoded to 16^3 types (voxel_model::chunk): region
// writes in whole x runs, which blocks ended up different, and how many voxels are solid.
// detail/edit.hpp runs these on many chunks at once.
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>

#include "voxray/core/box.hpp"
#include "voxray/edit/edit_op.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/naadf/layout.h"

namespace voxray {

namespace naadf_detail {

inline constexpr int chunk_edge = 1 << VX_NA_CHUNK_BITS;

// Solid voxels of a chunk: the high bit of each byte of (b & 0x7F) + 0x7F | b is set
// iff b != 0, so a 64-bit word counts 8 voxels at once.
inline std::int64_t solid_voxels(const voxel_model::chunk& c) {
    constexpr std::uint64_t low7 = 0x7F7F7F7F7F7F7F7Full;
    std::int64_t n = 0;
    for (std::size_t i = 0; i < c.voxels.size(); i += 8) {
        std::uint64_t w;
        std::memcpy(&w, c.voxels.data() + i, 8);
        n += std::popcount((((w & low7) + low7) | w) & ~low7);
    }
    return n;
}

// Bit b set: block b (the layout's block index) of the two chunks differs.
inline std::uint64_t changed_blocks(const voxel_model::chunk& a, const voxel_model::chunk& b) {
    std::uint64_t mask = 0;
    for (int row = 0; row < 256; ++row) {  // rows of 16 voxels: x blocks 0..3 of (y, z)
        std::uint32_t x[4], y[4];
        std::memcpy(x, a.voxels.data() + row * 16, 16);
        std::memcpy(y, b.voxels.data() + row * 16, 16);
        int base = ((row >> 2) & 3) << 2 | (row >> 6) << 4;  // block index of x block 0
        for (int i = 0; i < 4; ++i)
            if (x[i] != y[i]) mask |= std::uint64_t(1) << (base | i);
    }
    return mask;
}

inline box3i intersect(const box3i& a, const box3i& b) { return {glm::max(a.min, b.min), glm::min(a.max, b.max)}; }

// What op does to a voxel holding `old`.
inline std::uint8_t edited_value(edit_op op, std::uint8_t value, std::uint8_t old) {
    return op == edit_op::fill ? value : op == edit_op::erase ? 0 : (old ? value : 0);
}

// Region edit on the chunk at world position `origin` (voxels v), inside `world` only.
template <class Region>
bool write_region(const Region& region, edit_op op, std::uint8_t value, glm::ivec3 origin, const box3i& world,
                  voxel_model::chunk& v) {
    box3i q = intersect(intersect({origin, origin + chunk_edge}, region.bounds()), world);
    if (q.empty()) return false;
    bool changed = false;
    for (int z = q.min.z; z < q.max.z; ++z)
        for (int y = q.min.y; y < q.max.y; ++y) {
            auto [a, b] = region.span(y, z, q.min.x, q.max.x);
            if (a >= b) continue;
            std::uint8_t* first = v.voxels.data() + voxel_model::local_index({a, y, z});
            std::uint8_t* last = first + (b - a);
            if (op == edit_op::paint) {
                for (std::uint8_t* p = first; p < last; ++p) {
                    changed |= *p && *p != value;
                    *p = *p ? value : 0;
                }
                continue;
            }
            std::uint8_t fill = op == edit_op::fill ? value : 0;  // whole runs: compare, then set
            changed = changed || std::any_of(first, last, [&](std::uint8_t p) { return p != fill; });
            std::fill(first, last, fill);
        }
    return changed;
}

}  // namespace naadf_detail

}  // namespace voxray
