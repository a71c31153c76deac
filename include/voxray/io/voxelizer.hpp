// Conservative surface voxelization of a triangle mesh: a voxel is set iff its
// closed unit cube overlaps some triangle (exact SAT test, triangle_box.hpp).
//
// Grid: the mesh bounds are scaled uniformly so that the longest axis spans
// exactly `resolution` voxels; the bounds' minimum corner maps to voxel corner
// (0,0,0). Cells are clamped to [0, dims), so the model's bounds extent equals
// `resolution` on the longest axis exactly and is <= dims on the others.
//
// Streaming and parallel, never a dense grid of the world:
//   1. each triangle is binned into the 128^3-voxel tiles its closed surface
//      touches (SAT against the tile box);
//   2. worker threads take tiles, rasterize the tile's triangles into a 2 MiB
//      tile buffer laid out as the model's chunks, and hand back the touched
//      chunks, which are moved into the model at the end.
// Within a tile triangles run in file order and the first one to reach a voxel
// gives it its colour, so the result does not depend on the thread count.
#pragma once
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "voxray/core/error.hpp"
#include "voxray/io/group_palette.hpp"
#include "voxray/io/mesh.hpp"
#include "voxray/io/triangle_box.hpp"
#include "voxray/model/build_threads.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::io {

inline constexpr int max_voxelize_resolution = 4096;

// World -> voxel mapping shared by the voxelizer and the solid fill.
struct voxel_grid_map {
    glm::dvec3 origin{0.0};  // world position of voxel corner (0,0,0)
    double scale = 1.0;      // voxels per world unit
    glm::ivec3 dims{1};      // voxels per axis; the longest axis has `resolution`

    glm::dvec3 to_voxel(glm::dvec3 world) const { return (world - origin) * scale; }
};

inline voxel_grid_map make_grid_map(const mesh_bounds& b, int resolution) {
    if (resolution < 1 || resolution > max_voxelize_resolution)
        fail("voxelization resolution ", resolution, " is outside the supported range 1..", max_voxelize_resolution);
    auto ext = b.extent();
    int longest = ext.x >= ext.y && ext.x >= ext.z ? 0 : (ext.y >= ext.z ? 1 : 2);
    double scale = double(resolution) / ext[longest];
    if (!(ext[longest] > 0.0) || !std::isfinite(ext[longest]) || !std::isfinite(scale))
        fail("mesh has zero or non-finite extent (", ext[longest], "): cannot choose a voxel size");
    voxel_grid_map g;
    g.origin = b.min;
    g.scale = scale;
    for (int i = 0; i < 3; ++i) {
        // The small tolerance keeps 127.9999999 and 128.0000001 both at 128 voxels.
        double cells = std::ceil(ext[i] * g.scale - 1e-7);
        g.dims[i] = i == longest ? resolution : std::clamp(int(cells), 1, resolution);
    }
    return g;
}

struct voxelize_options {
    int resolution = 256;  // voxels along the longest axis of the mesh bounds, 1..4096
    unsigned threads = 0;  // 0: std::thread::hardware_concurrency()
};

namespace detail {

// Narrows [t0, t1] to where p + t (q - p) lies within [lo, hi]; false if empty.
inline bool clip_segment(double p, double q, double lo, double hi, double& t0, double& t1) {
    double d = q - p;
    if (d == 0.0) return p >= lo && p <= hi;
    double ta = (lo - p) / d, tb = (hi - p) / d;
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
    return t0 <= t1;
}

// First and last cell whose closed extent [m, m+1] meets [lo, hi], clamped to [a, b].
inline bool cell_span(double lo, double hi, int a, int b, int& first, int& last) {
    double f = std::max(double(a), std::ceil(lo) - 1.0), l = std::min(double(b), std::floor(hi));
    if (!(f <= l)) return false;
    first = int(f), last = int(l);
    return true;
}

// Calls emit(cell) for every cell in [lo, hi) (inclusive-exclusive) that the
// triangle overlaps. Candidates come row by row across the plane most facing
// the triangle (so each column holds at most ~3 candidates), and each candidate
// gets the exact test. `slack` widens candidate ranges against rounding; it never
// widens the exact test, which has its own far smaller slack.
template <class Emit>
void rasterize_triangle(const triangle_cell_test& tri, glm::ivec3 lo, glm::ivec3 hi, Emit&& emit) {
    constexpr double slack = 1e-7;
    glm::ivec3 first, last;
    for (int i = 0; i < 3; ++i)
        if (!cell_span(tri.bmin()[i] - slack, tri.bmax()[i] + slack, lo[i], hi[i] - 1, first[i], last[i])) return;
    glm::dvec3 n = tri.normal(), an = glm::abs(n);
    int w = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
    int u = (w + 1) % 3, v = (w + 2) % 3;
    double d = glm::dot(n, tri.vertex(0));
    const glm::dvec3* V[3] = {&tri.vertex(0), &tri.vertex(1), &tri.vertex(2)};
    for (int cv = first[v]; cv <= last[v]; ++cv) {
        // The u-extent of (triangle within the strip) is reached on its clipped edges.
        double umin = std::numeric_limits<double>::infinity(), umax = -umin;
        for (int k = 0; k < 3; ++k) {
            const glm::dvec3 &p = *V[k], &q = *V[(k + 1) % 3];
            double t0 = 0, t1 = 1;
            if (!clip_segment(p[v], q[v], cv - slack, cv + 1 + slack, t0, t1)) continue;
            double a = p[u] + t0 * (q[u] - p[u]), b = p[u] + t1 * (q[u] - p[u]);
            umin = std::min({umin, a, b});
            umax = std::max({umax, a, b});
        }
        int cu0, cu1;
        if (!cell_span(umin - slack, umax + slack, first[u], last[u], cu0, cu1)) continue;
        for (int cu = cu0; cu <= cu1; ++cu) {
            double wmin = std::numeric_limits<double>::infinity(), wmax = -wmin;
            if (n[w] != 0.0) {
                // The plane over the column's square: extremes at its corners (|slope| <= 1).
                for (int c = 0; c < 4; ++c) {
                    double U = cu + (c & 1), Vv = cv + (c >> 1);
                    double z = (d - n[u] * U - n[v] * Vv) / n[w];
                    wmin = std::min(wmin, z);
                    wmax = std::max(wmax, z);
                }
                wmin = std::max(wmin, tri.bmin()[w]);
                wmax = std::min(wmax, tri.bmax()[w]);
            } else {
                // Degenerate (a segment or a point): its edges are all of it.
                for (int k = 0; k < 3; ++k) {
                    const glm::dvec3 &p = *V[k], &q = *V[(k + 1) % 3];
                    double t0 = 0, t1 = 1;
                    if (!clip_segment(p[u], q[u], cu - slack, cu + 1 + slack, t0, t1)) continue;
                    if (!clip_segment(p[v], q[v], cv - slack, cv + 1 + slack, t0, t1)) continue;
                    double a = p[w] + t0 * (q[w] - p[w]), b = p[w] + t1 * (q[w] - p[w]);
                    wmin = std::min({wmin, a, b});
                    wmax = std::max({wmax, a, b});
                }
            }
            int cw0, cw1;
            if (!cell_span(wmin - slack, wmax + slack, first[w], last[w], cw0, cw1)) continue;
            glm::ivec3 cell;
            cell[u] = cu, cell[v] = cv;
            for (cell[w] = cw0; cell[w] <= cw1; ++cell[w])
                if (tri.overlaps(glm::dvec3(cell))) emit(cell);
        }
    }
}

inline constexpr int tile_chunks_bits = 3;                 // 8 chunks per tile axis
inline constexpr int tile_edge = voxel_model::chunk_edge << tile_chunks_bits;  // 128 voxels
inline constexpr int tile_chunk_count = 1 << (3 * tile_chunks_bits);           // 512

inline constexpr std::size_t max_tile_pairs = std::size_t(1) << 30;  // 4 GiB of ids

// Triangle ids per tile, in file order (a counting sort over (tile, triangle) pairs).
struct tile_bins {
    glm::ivec3 tiles{0};
    std::vector<std::size_t> offsets;      // per tile, into ids; size tiles + 1
    std::vector<std::uint32_t> ids;

    int tile_index(glm::ivec3 t) const { return (t.z * tiles.y + t.y) * tiles.x + t.x; }
    glm::ivec3 tile_coord(int i) const { return {i % tiles.x, (i / tiles.x) % tiles.y, i / (tiles.x * tiles.y)}; }
};

// Calls f(tile) for each tile whose closed box the triangle touches; the same
// candidate slack as rasterize_triangle, so no touching cell is lost at a border.
template <class ForTiles>
void for_each_tile_of(const glm::dvec3* v, const voxel_grid_map& g, ForTiles&& f) {
    constexpr double slack = 1e-7;
    glm::dvec3 bmin = glm::min(v[0], glm::min(v[1], v[2])), bmax = glm::max(v[0], glm::max(v[1], v[2]));
    glm::ivec3 c0, c1;
    for (int i = 0; i < 3; ++i)
        if (!cell_span(bmin[i] - slack, bmax[i] + slack, 0, g.dims[i] - 1, c0[i], c1[i])) return;
    glm::ivec3 t0 = c0 / tile_edge, t1 = c1 / tile_edge;
    bool single = t0 == t1;
    glm::ivec3 t;
    for (t.z = t0.z; t.z <= t1.z; ++t.z)
        for (t.y = t0.y; t.y <= t1.y; ++t.y)
            for (t.x = t0.x; t.x <= t1.x; ++t.x) {
                glm::dvec3 half(0.5 * tile_edge), centre = (glm::dvec3(t) + 0.5) * double(tile_edge);
                if (single || triangle_box_overlap(centre, half, v[0], v[1], v[2])) f(t);
            }
}

inline tile_bins bin_triangles(const std::vector<glm::dvec3>& vox, const triangle_mesh& mesh, const voxel_grid_map& g) {
    tile_bins bins;
    bins.tiles = (g.dims + (tile_edge - 1)) / tile_edge;
    std::size_t tile_total = std::size_t(bins.tiles.x) * bins.tiles.y * bins.tiles.z;
    std::vector<std::size_t> count(tile_total + 1, 0);
    auto corners = [&](std::size_t t, glm::dvec3* v) {
        for (int k = 0; k < 3; ++k) v[k] = vox[mesh.triangles[t][k]];
    };
    glm::dvec3 v[3];
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {  // pass 1: counts
        corners(t, v);
        for_each_tile_of(v, g, [&](glm::ivec3 c) { ++count[bins.tile_index(c)]; });
    }
    bins.offsets.assign(tile_total + 1, 0);
    for (std::size_t i = 0; i < tile_total; ++i) bins.offsets[i + 1] = bins.offsets[i] + count[i];
    // Huge triangles repeated many times could ask for billions of pairs.
    check_limit("voxelizer triangle/tile pair count", bins.offsets[tile_total], max_tile_pairs);
    bins.ids.resize(bins.offsets[tile_total]);
    std::vector<std::size_t> cursor(bins.offsets.begin(), bins.offsets.end() - 1);
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {  // pass 2: fill, file order kept
        corners(t, v);
        for_each_tile_of(v, g, [&](glm::ivec3 c) { bins.ids[cursor[bins.tile_index(c)]++] = std::uint32_t(t); });
    }
    return bins;
}

}  // namespace detail

// Voxelizes the surface of `mesh`. Palette: one colour per group (group_palette.hpp).
// The model's up_axis is left for the caller (load_mesh_model sets 1, Y up).
inline voxel_model voxelize(const triangle_mesh& mesh, const voxelize_options& opt = {}) {
    using namespace detail;
    if (mesh.triangles.empty()) fail("cannot voxelize a mesh with no triangles");
    mesh.validate();
    auto grid = make_grid_map(mesh.bounds(), opt.resolution);

    std::vector<glm::dvec3> vox(mesh.positions.size());
    for (std::size_t i = 0; i < vox.size(); ++i) vox[i] = grid.to_voxel(mesh.positions[i]);
    auto bins = bin_triangles(vox, mesh, grid);

    // Busiest tiles first, so the last tile to finish is a small one.
    std::vector<int> order;
    for (std::size_t i = 0; i + 1 < bins.offsets.size(); ++i)
        if (bins.offsets[i + 1] > bins.offsets[i]) order.push_back(int(i));
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
        return bins.offsets[a + 1] - bins.offsets[a] > bins.offsets[b + 1] - bins.offsets[b];
    });

    using chunk_ptr = std::unique_ptr<voxel_model::chunk>;
    struct placed_chunk {
        glm::ivec3 coord;
        chunk_ptr data;
    };
    unsigned threads = resolve_build_threads(opt.threads, order.size());
    std::vector<std::vector<placed_chunk>> results(threads);
    std::atomic<std::size_t> next{0};
    run_build_threads(threads, [&](unsigned id) {
        constexpr int cv = voxel_model::chunk_voxels;
        std::vector<std::uint8_t> buffer(std::size_t(tile_chunk_count) * cv, 0);  // chunk-major
        std::vector<int> touched;
        std::vector<char> is_touched(tile_chunk_count, 0);
        for (std::size_t k; (k = next.fetch_add(1)) < order.size();) {
            int tile = order[k];
            glm::ivec3 origin = bins.tile_coord(tile) * tile_edge;
            glm::ivec3 hi = glm::min(origin + tile_edge, grid.dims);
            for (auto i = bins.offsets[tile]; i < bins.offsets[tile + 1]; ++i) {
                std::uint32_t t = bins.ids[i];
                auto& ix = mesh.triangles[t];
                std::uint8_t colour = group_palette_index(mesh.group_of(t));
                triangle_cell_test test(vox[ix.x], vox[ix.y], vox[ix.z]);
                rasterize_triangle(test, origin, hi, [&](glm::ivec3 cell) {
                    glm::ivec3 l = (cell - origin) >> voxel_model::chunk_bits;
                    int lc = l.x | (l.y << tile_chunks_bits) | (l.z << (2 * tile_chunks_bits));
                    auto& b = buffer[std::size_t(lc) * cv + voxel_model::local_index(cell)];
                    if (!b) b = colour;  // first triangle in file order wins
                    if (!is_touched[lc]) { is_touched[lc] = 1; touched.push_back(lc); }
                });
            }
            for (int lc : touched) {
                auto c = std::make_unique<voxel_model::chunk>();
                std::uint8_t* src = buffer.data() + std::size_t(lc) * cv;
                std::memcpy(c->voxels.data(), src, cv);
                std::memset(src, 0, cv);
                is_touched[lc] = 0;
                glm::ivec3 l{lc & 7, (lc >> 3) & 7, lc >> 6};
                results[id].push_back({(origin >> voxel_model::chunk_bits) + l, std::move(c)});
            }
            touched.clear();
        }
    });

    voxel_model model;
    std::size_t total = 0;
    for (auto& r : results) total += r.size();
    model.reserve_chunks(total);
    for (auto& r : results)
        for (auto& pc : r) model.replace_chunk(pc.coord, std::move(pc.data));
    assign_group_palette(model.palette(), mesh.group_names);
    return model;
}

}  // namespace voxray::io
