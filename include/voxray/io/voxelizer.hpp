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
//
// Colour: one palette entry per group (group_palette.hpp), or, for a mesh with a coloured
// surface (io/mesh_surface.hpp), the colour of what each voxel covers (io/surface_sample.hpp;
// a triangle whose alpha rule drops it there leaves the voxel to the next one), then a
// palette of those colours by median cut (io/colour_palette.hpp).
//
// Work is bounded before it starts (issue 12, item 10): a triangle that repeats an
// earlier one exactly (the same three positions in the same order, whatever the
// indices) can change nothing, so it is dropped; and the cells the rest may test are
// estimated up front and checked against voxelize_options::max_cell_tests.
#pragma once
#include <algorithm>
#include <array>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <unordered_set>
#include <utility>
#include <vector>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "voxray/core/error.hpp"
#include "voxray/io/colour_palette.hpp"
#include "voxray/io/group_palette.hpp"
#include "voxray/io/mesh.hpp"
#include "voxray/io/surface_sample.hpp"
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

// `max_resolution`: a whole model in memory stops at 4096; a world built chunk by chunk
// (world/build/mesh_source.hpp) goes further.
inline voxel_grid_map make_grid_map(const mesh_bounds& b, int resolution, int max_resolution = max_voxelize_resolution) {
    if (resolution < 1 || resolution > max_resolution)
        fail("voxelization resolution ", resolution, " is outside the supported range 1..", max_resolution);
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
    // Upper bound of the estimated cell tests (see estimated_cell_tests); about 10 s a
    // 2^30 here. The shared meshes need well under 2^30 at resolution 4096.
    std::uint64_t max_cell_tests = std::uint64_t(1) << 32;
};

// What a voxelization did, for callers and tests (a count, not a time).
struct voxelize_stats {
    std::size_t triangles = 0;           // in the mesh
    std::size_t unique_triangles = 0;    // after exact duplicates were dropped
    std::uint64_t estimated_cells = 0;   // what max_cell_tests was checked against
    std::uint64_t rasterized = 0;        // (triangle, tile) pairs rasterized
    std::uint64_t cells_tested = 0;      // exact triangle/cell tests run
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
// `tested` (if given) counts the exact tests.
template <class Emit>
void rasterize_triangle(const triangle_cell_test& tri, glm::ivec3 lo, glm::ivec3 hi, std::uint64_t* tested,
                        Emit&& emit) {
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
            if (tested) *tested += std::uint64_t(cw1 - cw0 + 1);
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

// Triangles in file order without exact repeats of an earlier one (same positions, same
// order; compared bitwise, so -0 and 0 differ and nothing is merged by mistake).
inline std::vector<std::uint32_t> unique_triangles(const triangle_mesh& mesh) {
    using key = std::array<std::uint64_t, 9>;
    struct key_hash {
        std::size_t operator()(const key& k) const {
            std::uint64_t h = 0x9e3779b97f4a7c15ull;
            for (auto w : k) h = (h ^ w) * 0x100000001b3ull, h ^= h >> 29;
            return std::size_t(h);
        }
    };
    std::unordered_set<key, key_hash> seen;
    seen.reserve(mesh.triangles.size());
    std::vector<std::uint32_t> ids;
    ids.reserve(mesh.triangles.size());
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
        key k;
        for (int c = 0; c < 3; ++c)
            for (int a = 0; a < 3; ++a) k[3 * c + a] = std::bit_cast<std::uint64_t>(mesh.positions[mesh.triangles[t][c]][a]);
        if (seen.insert(k).second) ids.push_back(std::uint32_t(t));
    }
    return ids;
}

// Cells rasterize_triangle may test for a triangle in voxel units: the columns it
// covers on its most facing plane (area plus a border of one cell along its edges),
// up to three cells deep each (the plane's slope there is at most 1).
inline double estimated_cell_tests(const glm::dvec3* v) {
    glm::dvec3 n = glm::cross(v[1] - v[0], v[2] - v[0]), an = glm::abs(n);
    int w = an.x >= an.y && an.x >= an.z ? 0 : (an.y >= an.z ? 1 : 2);
    int u = (w + 1) % 3, vv = (w + 2) % 3;
    double border = 0;
    for (int k = 0; k < 3; ++k) {
        glm::dvec3 e = v[(k + 1) % 3] - v[k];
        border += std::abs(e[u]) + std::abs(e[vv]);
    }
    return 3.0 * (0.5 * an[w] + border + 4.0);
}

inline tile_bins bin_triangles(const std::vector<glm::dvec3>& vox, const triangle_mesh& mesh,
                               const std::vector<std::uint32_t>& triangles, const voxel_grid_map& g) {
    tile_bins bins;
    bins.tiles = (g.dims + (tile_edge - 1)) / tile_edge;
    std::size_t tile_total = std::size_t(bins.tiles.x) * bins.tiles.y * bins.tiles.z;
    std::vector<std::size_t> count(tile_total + 1, 0);
    auto corners = [&](std::size_t t, glm::dvec3* v) {
        for (int k = 0; k < 3; ++k) v[k] = vox[mesh.triangles[t][k]];
    };
    glm::dvec3 v[3];
    for (std::uint32_t t : triangles) {  // pass 1: counts
        corners(t, v);
        for_each_tile_of(v, g, [&](glm::ivec3 c) { ++count[bins.tile_index(c)]; });
    }
    bins.offsets.assign(tile_total + 1, 0);
    for (std::size_t i = 0; i < tile_total; ++i) bins.offsets[i + 1] = bins.offsets[i] + count[i];
    // Huge triangles repeated many times could ask for billions of pairs.
    check_limit("voxelizer triangle/tile pair count", bins.offsets[tile_total], max_tile_pairs);
    bins.ids.resize(bins.offsets[tile_total]);
    std::vector<std::size_t> cursor(bins.offsets.begin(), bins.offsets.end() - 1);
    for (std::uint32_t t : triangles) {  // pass 2: fill, file order kept
        corners(t, v);
        for_each_tile_of(v, g, [&](glm::ivec3 c) { bins.ids[cursor[bins.tile_index(c)]++] = t; });
    }
    return bins;
}

// Coloured meshes: a palette of the voxels' colours (median cut, 255 entries), and each
// voxel's material set to its colour's entry. `Results` are the threads' placed chunks.
template <class Results>
void colour_voxels(Results& results, palette& pal) {
    std::unordered_map<std::uint32_t, std::uint64_t> histogram;
    for (auto& r : results)
        for (auto& pc : r)
            for (std::size_t i = 0; i < pc.colours.size(); ++i)
                if (pc.data->voxels[i]) ++histogram[pc.colours[i]];
    std::vector<colour_count> counts;
    for (auto [rgb, n] : histogram) counts.push_back({rgb, n});
    median_cut_palette cut = median_cut(std::move(counts), 255);
    for (std::size_t e = 0; e < cut.entries.size(); ++e) pal[std::uint8_t(e + 1)].colour = cut.entries[e];
    for (auto& r : results)
        for (auto& pc : r)
            for (std::size_t i = 0; i < pc.colours.size(); ++i)
                if (pc.data->voxels[i]) pc.data->voxels[i] = std::uint8_t(1 + cut.entry.at(pc.colours[i]));
}

}  // namespace detail

// Voxelizes the surface of `mesh`. Palette: one colour per group (group_palette.hpp), or
// the surface's colours (see the top of this file).
// The model's up_axis is left for the caller (load_mesh_model sets 1, Y up).
inline voxel_model voxelize(const triangle_mesh& mesh, const voxelize_options& opt = {},
                            voxelize_stats* stats_out = nullptr) {
    using namespace detail;
    if (mesh.triangles.empty()) fail("cannot voxelize a mesh with no triangles");
    mesh.validate();
    auto grid = make_grid_map(mesh.bounds(), opt.resolution);

    std::vector<glm::dvec3> vox(mesh.positions.size());
    for (std::size_t i = 0; i < vox.size(); ++i) vox[i] = grid.to_voxel(mesh.positions[i]);
    voxelize_stats stats;
    stats.triangles = mesh.triangles.size();
    auto triangles = unique_triangles(mesh);
    stats.unique_triangles = triangles.size();
    double estimate = 0;
    for (std::uint32_t t : triangles) {
        glm::dvec3 v[3] = {vox[mesh.triangles[t].x], vox[mesh.triangles[t].y], vox[mesh.triangles[t].z]};
        estimate += estimated_cell_tests(v);
    }
    stats.estimated_cells = std::uint64_t(std::min(estimate, 1.8e19));
    if (stats.estimated_cells > opt.max_cell_tests)
        fail("voxelizing ", stats.unique_triangles, " distinct triangles (of ", stats.triangles, ") at resolution ",
             opt.resolution, " would test about ", stats.estimated_cells, " cells, above the limit of ",
             opt.max_cell_tests, " (voxelize_options::max_cell_tests)");
    auto bins = bin_triangles(vox, mesh, triangles, grid);

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
        std::vector<std::uint32_t> colours;  // coloured meshes: sRGB r | g << 8 | b << 16 per voxel
    };
    const bool coloured = mesh.surface.coloured();
    unsigned threads = resolve_build_threads(opt.threads, order.size());
    std::vector<std::vector<placed_chunk>> results(threads);
    std::atomic<std::size_t> next{0};
    std::atomic<std::uint64_t> cells_tested{0};
    run_build_threads(threads, [&](unsigned id) {
        constexpr int cv = voxel_model::chunk_voxels;
        std::vector<std::uint8_t> buffer(std::size_t(tile_chunk_count) * cv, 0);  // chunk-major
        std::vector<std::uint32_t> colours(coloured ? buffer.size() : 0);
        std::vector<int> touched;
        std::vector<char> is_touched(tile_chunk_count, 0);
        std::uint64_t tested = 0;
        for (std::size_t k; (k = next.fetch_add(1)) < order.size();) {
            int tile = order[k];
            glm::ivec3 origin = bins.tile_coord(tile) * tile_edge;
            glm::ivec3 hi = glm::min(origin + tile_edge, grid.dims);
            for (auto i = bins.offsets[tile]; i < bins.offsets[tile + 1]; ++i) {
                std::uint32_t t = bins.ids[i];
                auto& ix = mesh.triangles[t];
                std::uint8_t colour = group_palette_index(mesh.group_of(t));
                const glm::dvec3 corners[3] = {vox[ix.x], vox[ix.y], vox[ix.z]};
                triangle_cell_test test(corners[0], corners[1], corners[2]);
                rasterize_triangle(test, origin, hi, &tested, [&](glm::ivec3 cell) {
                    glm::ivec3 l = (cell - origin) >> voxel_model::chunk_bits;
                    int lc = l.x | (l.y << tile_chunks_bits) | (l.z << (2 * tile_chunks_bits));
                    std::size_t at = std::size_t(lc) * cv + voxel_model::local_index(cell);
                    auto& b = buffer[at];
                    if (b) return;  // first triangle in file order wins
                    if (coloured) {
                        std::optional<rgba> c = voxel_colour(mesh.surface, t, corners, cell);
                        if (!c) return;  // transparent here: the voxel stays for another triangle
                        colours[at] = std::uint32_t(c->r) | std::uint32_t(c->g) << 8 | std::uint32_t(c->b) << 16;
                    }
                    b = colour;
                    if (!is_touched[lc]) { is_touched[lc] = 1; touched.push_back(lc); }
                });
            }
            for (int lc : touched) {
                auto c = std::make_unique<voxel_model::chunk>();
                std::uint8_t* src = buffer.data() + std::size_t(lc) * cv;
                std::memcpy(c->voxels.data(), src, cv);
                std::memset(src, 0, cv);
                std::vector<std::uint32_t> chunk_colours;
                if (coloured) {
                    auto first = colours.begin() + std::ptrdiff_t(std::size_t(lc) * cv);
                    chunk_colours.assign(first, first + cv);
                }
                is_touched[lc] = 0;
                glm::ivec3 l{lc & 7, (lc >> 3) & 7, lc >> 6};
                results[id].push_back(
                    {(origin >> voxel_model::chunk_bits) + l, std::move(c), std::move(chunk_colours)});
            }
            touched.clear();
        }
        cells_tested += tested;
    });
    stats.rasterized = bins.ids.size();
    stats.cells_tested = cells_tested;
    if (stats_out) *stats_out = stats;

    voxel_model model;
    std::size_t total = 0;
    for (auto& r : results) total += r.size();
    model.reserve_chunks(total);
    if (coloured) colour_voxels(results, model.palette());
    for (auto& r : results)
        for (auto& pc : r) model.replace_chunk(pc.coord, std::move(pc.data));
    if (!coloured) assign_group_palette(model.palette(), mesh.group_names);
    return model;
}

}  // namespace voxray::io
