// Quads as a level of detail draws them: corners rounded down to multiples of 2^level
// (chunk-local rounding is the world's: chunk origins are multiples of 64), and per face
// direction and rounded plane, how often each cell of the 2^level grid is covered. The
// squashed-face pass and the overdraw statistics read the same numbers.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "voxray/meshing/chunk_mesh.hpp"
#include "voxray/meshing/layout.h"

namespace voxray::meshing {

struct rounded_quad {
    std::uint32_t index = 0;  // in the mesh
    int plane = 0;            // rounded coordinate along the normal, in cells (0..64 >> level)
    int u0 = 0, u1 = 0, v0 = 0, v1 = 0;  // rounded rectangle, in cells
};

// Rounded quads of face `face` drawn at `level` (those with a level above it).
inline std::vector<rounded_quad> rounded_quads(const chunk_mesh& m, int face, int level) {
    std::vector<rounded_quad> out;
    for (std::uint32_t i = m.face_begin(face); i < m.face_end(face, level); ++i) {
        quad q = m.at(i);
        int n = int(VX_MESH_NORMAL_AXIS(face)), u = int(VX_MESH_U_AXIS(face)), v = int(VX_MESH_V_AXIS(face));
        int plane = q.voxel[n] + (VX_MESH_POSITIVE(face) ? 1 : 0);
        out.push_back({i, plane >> level, q.voxel[u] >> level, (q.voxel[u] + q.w) >> level, q.voxel[v] >> level,
                       (q.voxel[v] + q.h) >> level});
    }
    return out;
}

// Cover counts of one plane's cells, (64 >> level) + 1 on a side.
class plane_cover {
public:
    explicit plane_cover(int level) : side_((VX_MESH_CHUNK_EDGE >> level) + 1), counts_(std::size_t(side_) * side_, 0) {}

    void add(const rounded_quad& r, int delta) {
        for (int v = r.v0; v < r.v1; ++v)
            for (int u = r.u0; u < r.u1; ++u) counts_[std::size_t(v) * side_ + u] += delta;
    }
    // True when every cell of r is covered at least twice.
    bool covered_twice(const rounded_quad& r) const {
        for (int v = r.v0; v < r.v1; ++v)
            for (int u = r.u0; u < r.u1; ++u)
                if (counts_[std::size_t(v) * side_ + u] < 2) return false;
        return true;
    }
    const std::vector<std::uint16_t>& counts() const { return counts_; }

private:
    int side_;
    std::vector<std::uint16_t> counts_;
};

// Calls f(face, plane, cover) for every face direction and rounded plane with a quad drawn
// at `level`, the quads of that plane in `quads`.
template <class F>
void for_each_rounded_plane(const chunk_mesh& m, int level, F&& f) {
    for (int face = 0; face < VX_MESH_FACES; ++face) {
        auto quads = rounded_quads(m, face, level);
        std::stable_sort(quads.begin(), quads.end(), [](auto& a, auto& b) { return a.plane < b.plane; });
        for (std::size_t begin = 0; begin < quads.size();) {
            std::size_t end = begin;
            while (end < quads.size() && quads[end].plane == quads[begin].plane) ++end;
            std::vector<rounded_quad> in_plane(quads.begin() + std::ptrdiff_t(begin), quads.begin() + std::ptrdiff_t(end));
            f(face, quads[begin].plane, in_plane);
            begin = end;
        }
    }
}

// Cells drawn at `level` (counted once per face direction and plane) and their cover sum:
// overdraw = covered_sum / cells.
struct overdraw_count {
    std::uint64_t cells = 0, covered_sum = 0;
    double ratio() const { return cells ? double(covered_sum) / double(cells) : 1.0; }
};

inline overdraw_count overdraw(const chunk_mesh& m, int level) {
    overdraw_count total;
    for_each_rounded_plane(m, level, [&](int, int, const std::vector<rounded_quad>& quads) {
        plane_cover cover(level);
        for (auto& r : quads) cover.add(r, 1);
        for (auto c : cover.counts())
            if (c) total.cells += 1, total.covered_sum += c;
    });
    return total;
}

}  // namespace voxray::meshing
