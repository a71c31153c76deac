// The squashed-face pass: rounding moves planes together, so at a coarse level quads of one
// face direction can land on top of each other (noise: 2x to 8x overdraw). For each level
// from 1 up, a quad whose rounded rectangle is already covered twice or more in its plane
// by the quads still drawn leaves that level: its level becomes that level, so it is drawn
// only at finer ones. What a level draws covers the very same cells per face direction and
// plane as before, so the image and its closedness do not change (the tests check both).
// Among the candidates the finer quads go first: they were about to vanish anyway.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "voxray/meshing/chunk_mesh.hpp"
#include "voxray/meshing/rounded.hpp"

namespace voxray::meshing {

// Re-sorts each face's quads coarse to fine by their level fields (stable) and rebuilds the
// table, after levels were changed.
inline void sort_pop_order(chunk_mesh& m) {
    std::vector<std::uint32_t> sorted;
    sorted.reserve(m.words.size());
    std::array<std::uint32_t, VX_MESH_TABLE_ENTRIES> table{};
    for (int f = 0; f < VX_MESH_FACES; ++f) {
        std::uint32_t begin = m.face_begin(f), end = m.face_end(f, 0);
        for (int level = VX_MESH_MAX_LEVEL; level >= 1; --level) {
            for (std::uint32_t i = begin; i < end; ++i)
                if (int(VX_MESH_LEVEL(m.words[2 * i + 1])) == level) sorted.insert(sorted.end(), {m.words[2 * i], m.words[2 * i + 1]});
            table[VX_MESH_TABLE_END(f, level - 1)] = std::uint32_t(sorted.size() / VX_MESH_QUAD_WORDS);
        }
    }
    m.words = std::move(sorted);
    m.table = table;
}

struct squashed_stats {
    std::uint32_t moved = 0;  // quads whose level was lowered
};

inline squashed_stats remove_squashed_faces(chunk_mesh& m) {
    squashed_stats stats;
    for (int level = 1; level < VX_MESH_LEVELS; ++level) {
        bool changed = false;
        for_each_rounded_plane(m, level, [&](int, int, std::vector<rounded_quad>& quads) {
            if (quads.size() < 2) return;
            plane_cover cover(level);
            for (auto& r : quads) cover.add(r, 1);
            auto finer_first = [&](const rounded_quad& a, const rounded_quad& b) {
                int la = int(VX_MESH_LEVEL(m.words[2 * a.index + 1])), lb = int(VX_MESH_LEVEL(m.words[2 * b.index + 1]));
                if (la != lb) return la < lb;
                return (a.u1 - a.u0) * (a.v1 - a.v0) < (b.u1 - b.u0) * (b.v1 - b.v0);
            };
            std::stable_sort(quads.begin(), quads.end(), finer_first);
            for (auto& r : quads) {
                if (!cover.covered_twice(r)) continue;
                cover.add(r, -1);
                std::uint32_t& w1 = m.words[2 * r.index + 1];
                w1 = VX_MESH_WITH_LEVEL(w1, std::uint32_t(level));
                ++stats.moved;
                changed = true;
            }
        });
        if (changed) sort_pop_order(m);
    }
    return stats;
}

}  // namespace voxray::meshing
