// Crack tests for POP chunk meshes, exact (integers, or float bits):
//  (a) closedness: at each level of detail, drawn everywhere, the oriented edges of all
//      rounded quads of all chunks cancel on every axis line (a 1-D cover count, so
//      T-junctions count too); and the squashed-face pass leaves every plane's covered
//      cells as they were, so what it draws is the same closed surface;
//  (b) a vertex that two chunks share morphs to bit-identical positions from both;
//  (c) every T-vertex stays on its host edge after morphing.
// (b) and (c) run per view: an eye and a bias, so that neighbouring cells get different t.
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <map>
#include <tuple>
#include <vector>

#include "voxray/core/box.hpp"
#include "voxray/meshing/chunk_mesh.hpp"
#include "voxray/meshing/pop.hpp"
#include "voxray/meshing/rounded.hpp"
#include "voxray/scenes/noise.hpp"

namespace voxray::check {

namespace cracks_detail {

// An axis line: the axis and the two other coordinates.
inline std::uint64_t line_key(int axis, glm::ivec3 p) {
    int a = (axis + 1) % 3, b = (axis + 2) % 3;
    constexpr std::int64_t bias = std::int64_t(1) << 29;
    return (std::uint64_t(axis) << 60) | (std::uint64_t(p[a] + bias) << 30) | std::uint64_t(p[b] + bias);
}

// Calls f(corner 0..3 world positions, orientation +1/-1) for each quad of `m` drawn at `level`.
template <class F>
void for_each_drawn_quad(const meshing::chunk_mesh& m, int level, F&& f) {
    for (int face = 0; face < VX_MESH_FACES; ++face)
        for (std::uint32_t i = m.face_begin(face); i < m.face_end(face, level); ++i) {
            glm::ivec3 c[4];
            for (int k = 0; k < 4; ++k) c[k] = meshing::quad_corner(m.words[2 * i], m.words[2 * i + 1], k, m.origin);
            f(c, VX_MESH_POSITIVE(face) ? 1 : -1);
        }
}

}  // namespace cracks_detail

// (a) The axis lines at `level` whose oriented edge cover does not cancel somewhere.
inline std::uint64_t open_lines(const std::vector<meshing::chunk_mesh>& meshes, int level) {
    struct event {
        std::uint64_t line;
        int position, delta;
    };
    std::vector<event> events;
    const int mask = ~((1 << level) - 1);
    for (const auto& m : meshes)
        cracks_detail::for_each_drawn_quad(m, level, [&](const glm::ivec3* c, int sign) {
            for (int k = 0; k < 4; ++k) {
                glm::ivec3 p = c[k] & mask, q = c[(k + 1) % 4] & mask;
                if (p == q) continue;
                int axis = p.x != q.x ? 0 : p.y != q.y ? 1 : 2;
                int delta = p[axis] < q[axis] ? sign : -sign;
                std::uint64_t line = cracks_detail::line_key(axis, p);
                events.push_back({line, std::min(p[axis], q[axis]), delta});
                events.push_back({line, std::max(p[axis], q[axis]), -delta});
            }
        });
    std::sort(events.begin(), events.end(), [](const event& a, const event& b) {
        return std::tie(a.line, a.position) < std::tie(b.line, b.position);
    });
    std::uint64_t open = 0;
    for (std::size_t i = 0; i < events.size();) {
        std::uint64_t line = events[i].line;
        int running = 0;
        bool bad = false;
        for (; i < events.size() && events[i].line == line; ++i) {
            running += events[i].delta;
            bool position_done = i + 1 == events.size() || events[i + 1].line != line || events[i + 1].position != events[i].position;
            if (position_done && running != 0) bad = true;
        }
        open += bad;
    }
    return open;
}

// (a) after the squashed-face pass: the planes (face, rounded plane, cell) whose coverage at
// `level` differs between `before` and `after`.
inline std::uint64_t coverage_changes(const meshing::chunk_mesh& before, const meshing::chunk_mesh& after, int level) {
    auto covered = [level](const meshing::chunk_mesh& m) {
        std::vector<std::uint64_t> cells;  // face, plane, v, u: 3, 8, 8, 8 bits
        meshing::for_each_rounded_plane(m, level, [&](int face, int plane, const std::vector<meshing::rounded_quad>& quads) {
            for (auto& r : quads)
                for (int v = r.v0; v < r.v1; ++v)
                    for (int u = r.u0; u < r.u1; ++u)
                        cells.push_back(std::uint64_t(face) << 24 | std::uint64_t(plane) << 16 | std::uint64_t(v) << 8 | std::uint64_t(u));
        });
        std::sort(cells.begin(), cells.end());
        cells.erase(std::unique(cells.begin(), cells.end()), cells.end());
        return cells;
    };
    auto a = covered(before), b = covered(after);
    std::vector<std::uint64_t> diff;
    std::set_symmetric_difference(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(diff));
    return diff.size();
}

// (b) and (c): what the views test, found once.
struct morph_cases {
    // Per shared vertex: the chunks' quad corners that land on it (mesh, quad, corner).
    std::vector<std::vector<std::tuple<std::uint32_t, std::uint32_t, int>>> shared;
    // T-junctions: (host edge start, T-vertex, host edge end), indices into t_positions.
    std::vector<std::tuple<std::uint32_t, std::uint32_t, std::uint32_t>> t_junctions;
    std::vector<glm::ivec3> t_positions;  // each once: a view morphs each once
};

inline morph_cases find_morph_cases(const std::vector<meshing::chunk_mesh>& meshes) {
    morph_cases cases;
    std::map<std::tuple<int, int, int>, std::vector<std::tuple<std::uint32_t, std::uint32_t, int>>> corners;
    std::map<std::uint64_t, std::vector<int>> on_line[3];  // vertex positions along each axis line
    for (std::uint32_t mi = 0; mi < meshes.size(); ++mi) {
        const auto& m = meshes[mi];
        for (std::uint32_t qi = 0; qi < m.quad_count(); ++qi)
            for (int k = 0; k < 4; ++k) {
                glm::ivec3 p = meshing::quad_corner(m.words[2 * qi], m.words[2 * qi + 1], k, m.origin);
                corners[{p.x, p.y, p.z}].emplace_back(mi, qi, k);
                for (int axis = 0; axis < 3; ++axis) on_line[axis][cracks_detail::line_key(axis, p)].push_back(p[axis]);
            }
    }
    for (auto& [p, list] : corners) {
        const auto first_chunk = std::get<0>(list[0]);  // a copy: clang 14 cannot capture a structured binding
        bool two_chunks = std::any_of(list.begin(), list.end(), [&](auto& e) { return std::get<0>(e) != first_chunk; });
        if (two_chunks) cases.shared.push_back(list);
    }
    for (auto& lines : on_line)
        for (auto& [key, positions] : lines) {
            std::sort(positions.begin(), positions.end());
            positions.erase(std::unique(positions.begin(), positions.end()), positions.end());
        }
    std::map<std::tuple<int, int, int>, std::uint32_t> t_index;
    auto index_of = [&](glm::ivec3 p) {
        auto [it, added] = t_index.try_emplace({p.x, p.y, p.z}, std::uint32_t(cases.t_positions.size()));
        if (added) cases.t_positions.push_back(p);
        return it->second;
    };
    for (const auto& m : meshes)
        for (std::uint32_t qi = 0; qi < m.quad_count(); ++qi)
            for (int k = 0; k < 4; ++k) {
                glm::ivec3 a = meshing::quad_corner(m.words[2 * qi], m.words[2 * qi + 1], k, m.origin);
                glm::ivec3 b = meshing::quad_corner(m.words[2 * qi], m.words[2 * qi + 1], (k + 1) % 4, m.origin);
                int axis = a.x != b.x ? 0 : a.y != b.y ? 1 : 2;
                const auto& positions = on_line[axis][cracks_detail::line_key(axis, a)];
                int lo = std::min(a[axis], b[axis]), hi = std::max(a[axis], b[axis]);
                for (auto it = std::upper_bound(positions.begin(), positions.end(), lo); it != positions.end() && *it < hi; ++it) {
                    glm::ivec3 v = a;
                    v[axis] = *it;
                    cases.t_junctions.emplace_back(index_of(a), index_of(v), index_of(b));
                }
            }
    return cases;
}

struct morph_result {
    std::uint64_t views = 0, shared_checks = 0, t_checks = 0;
    std::uint64_t split_vertices = 0;  // (b) failures
    std::uint64_t t_vertices_off = 0;  // (c) failures
};

// Random views around `bounds`: eyes within it and 64 voxels around, biases in [-1, 4].
inline morph_result check_morphs(const std::vector<meshing::chunk_mesh>& meshes, const morph_cases& cases, box3i bounds,
                                 int views, std::uint64_t seed) {
    morph_result r;
    scenes::rng g{seed};
    std::vector<glm::vec3> morphed;
    glm::vec3 lo = glm::vec3(bounds.min) - 64.0f, size = glm::vec3(bounds.extent()) + 128.0f;
    for (int view = 0; view < views; ++view, ++r.views) {
        meshing::pop_view v;
        v.eye = lo + size * glm::vec3(float(g.uniform()), float(g.uniform()), float(g.uniform()));
        v.bias = float(-1.0 + 5.0 * g.uniform());
        for (const auto& list : cases.shared) {
            glm::vec3 first{};
            for (std::size_t i = 0; i < list.size(); ++i) {
                auto [mi, qi, k] = list[i];
                const auto& m = meshes[mi];
                glm::vec3 p = meshing::pop_vertex(meshing::quad_corner(m.words[2 * qi], m.words[2 * qi + 1], k, m.origin), v);
                if (i == 0) first = p;
                else if (std::memcmp(&p, &first, sizeof p) != 0) ++r.split_vertices;
                ++r.shared_checks;
            }
        }
        morphed.resize(cases.t_positions.size());
        for (std::size_t i = 0; i < morphed.size(); ++i) morphed[i] = meshing::pop_vertex(cases.t_positions[i], v);
        for (auto& [a, t, b] : cases.t_junctions) {
            glm::vec3 pa = morphed[a], pt = morphed[t], pb = morphed[b];
            glm::ivec3 ia = cases.t_positions[a], ib = cases.t_positions[b];
            int axis = ia.x != ib.x ? 0 : ia.y != ib.y ? 1 : 2;
            bool on_edge = std::min(pa[axis], pb[axis]) <= pt[axis] && pt[axis] <= std::max(pa[axis], pb[axis]);
            for (int other = 0; other < 3; ++other)
                if (other != axis) on_edge = on_edge && pa[other] == pt[other] && pb[other] == pt[other];
            r.t_vertices_off += !on_edge;
            ++r.t_checks;
        }
    }
    return r;
}

}  // namespace voxray::check
