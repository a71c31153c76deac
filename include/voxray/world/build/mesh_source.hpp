// A triangle mesh as the source of a world build (world/build/world_build.hpp), voxelized one
// chunk at a time: the triangles are binned once into the voxelizer's 128^3 tiles, and a
// cell's voxels are those its tiles' triangles cover within the cell (the voxelizer's
// conservative rule, io/voxelizer.hpp: a voxel is set iff its closed cube meets a
// triangle; the first triangle in file order gives its colour). So the voxels of the whole
// world never exist at once, and a mesh can be voxelized past the 4096 a whole-model
// voxelization allows.
#pragma once
#include <algorithm>
#include <cstdint>
#include <set>
#include <vector>

#include "voxray/core/checksum.hpp"
#include "voxray/io/voxelizer.hpp"
#include "voxray/world/chunk_voxels.hpp"
#include "voxray/world/world_blob.hpp"

namespace voxray {

inline constexpr int max_world_mesh_resolution = 1 << 16;

// The hash of a mesh_source: of the mesh's positions, triangles and groups and the resolution
// (what a world build records in its manifest, with its options: world_source_hash).
inline std::uint32_t mesh_source_hash(const io::triangle_mesh& mesh, int resolution) {
    fnv64 h;
    h.bytes(mesh.positions.data(), mesh.positions.size() * sizeof(mesh.positions[0]));
    h.bytes(mesh.triangles.data(), mesh.triangles.size() * sizeof(mesh.triangles[0]));
    h.bytes(mesh.groups.data(), mesh.groups.size() * sizeof(mesh.groups[0]));
    h.bytes(&resolution, sizeof resolution);
    return std::uint32_t(h.h ^ (h.h >> 32));
}

class mesh_source {
public:
    // `max_cell_tests`: the bound on the voxelization's work (voxelize_options), scaled
    // for big worlds: about 10 s a 2^30 here.
    mesh_source(const io::triangle_mesh& mesh, int resolution, std::uint64_t max_cell_tests = std::uint64_t(1) << 36)
        : mesh_(&mesh), resolution_(resolution) {
        using namespace io::detail;
        if (mesh.triangles.empty()) fail("cannot build a world from a mesh with no triangles");
        mesh.validate();
        map_ = io::make_grid_map(mesh.bounds(), resolution, max_world_mesh_resolution);
        vox_.resize(mesh.positions.size());
        for (std::size_t i = 0; i < vox_.size(); ++i) vox_[i] = map_.to_voxel(mesh.positions[i]);
        auto triangles = unique_triangles(mesh);
        double estimate = 0;
        for (std::uint32_t t : triangles) {
            glm::dvec3 v[3] = {vox_[mesh.triangles[t].x], vox_[mesh.triangles[t].y], vox_[mesh.triangles[t].z]};
            estimate += estimated_cell_tests(v);
        }
        if (estimate > double(max_cell_tests))
            fail("voxelizing ", triangles.size(), " distinct triangles at resolution ", resolution, " would test about ",
                 std::uint64_t(estimate), " cells, above the limit of ", max_cell_tests);
        bins_ = bin_triangles(vox_, mesh, triangles, map_);
        io::assign_group_palette(palette_, mesh.group_names);
    }

    box3i bounds() const { return {glm::ivec3(0), map_.dims}; }
    std::uint32_t hash() const { return mesh_source_hash(*mesh_, resolution_); }
    const palette& colours() const { return palette_; }

    // The cells that tiles with triangles overlap.
    std::vector<glm::ivec3> cells(const world_grid& g) const {
        std::set<glm::ivec3, ivec3_less> out;
        for_each_tile_cell(g, [&](glm::ivec3 cell, std::uint64_t) { out.insert(cell); });
        return {out.begin(), out.end()};
    }

    // The work of each of `cells` (sorted, as cells() gives them): the triangles binned
    // to the tiles it overlaps. An estimate that balances shards.
    std::vector<std::uint64_t> cell_work(const world_grid& g, const std::vector<glm::ivec3>& cells) const {
        std::vector<std::uint64_t> work(cells.size(), 0);
        for_each_tile_cell(g, [&](glm::ivec3 cell, std::uint64_t triangles) {
            auto it = std::lower_bound(cells.begin(), cells.end(), cell, ivec3_less{});
            if (it != cells.end() && *it == cell) work[std::size_t(it - cells.begin())] += triangles;
        });
        return work;
    }

    // The cell's voxels (thread-safe: all state is the call's own).
    chunk_voxels voxels(const world_grid& g, glm::ivec3 cell, bool colours) const {
        using namespace io::detail;
        glm::ivec3 cell_lo = g.origin + (cell << g.chunk_bits), cell_hi = cell_lo + g.edge();
        std::vector<std::uint64_t> seen((std::size_t(1) << (3 * g.chunk_bits)) / 64 + 1, 0);
        chunk_voxels out;
        glm::ivec3 t0 = glm::max(cell_lo, glm::ivec3(0)) / tile_edge;
        glm::ivec3 t1 = (glm::min(cell_hi, map_.dims) - 1) / tile_edge;
        for (int tz = t0.z; tz <= t1.z; ++tz)
            for (int ty = t0.y; ty <= t1.y; ++ty)
                for (int tx = t0.x; tx <= t1.x; ++tx) {
                    int tile = bins_.tile_index({tx, ty, tz});
                    glm::ivec3 lo = glm::max(glm::ivec3(tx, ty, tz) * tile_edge, cell_lo);
                    glm::ivec3 hi = glm::min(glm::min((glm::ivec3(tx, ty, tz) + 1) * tile_edge, cell_hi), map_.dims);
                    for (auto i = bins_.offsets[std::size_t(tile)]; i < bins_.offsets[std::size_t(tile) + 1]; ++i) {
                        std::uint32_t t = bins_.ids[i];
                        auto& ix = mesh_->triangles[t];
                        std::uint8_t index = io::group_palette_index(mesh_->group_of(t));
                        io::triangle_cell_test test(vox_[ix.x], vox_[ix.y], vox_[ix.z]);
                        rasterize_triangle(test, lo, hi, nullptr, [&](glm::ivec3 p) {
                            glm::ivec3 l = p - cell_lo;
                            std::size_t bit = std::size_t(l.x) | (std::size_t(l.y) << g.chunk_bits) | (std::size_t(l.z) << (2 * g.chunk_bits));
                            if (seen[bit >> 6] >> (bit & 63) & 1u) return;  // an earlier triangle gave its colour
                            seen[bit >> 6] |= std::uint64_t(1) << (bit & 63);
                            out.keys.push_back(chunk_voxels::key(l));
                            out.values.push_back(colours ? pack_rgba(palette_[index].colour) : index);
                        });
                    }
                }
        out.sort();
        return out;
    }

private:
    // f(cell, triangles) for every cell a tile with triangles overlaps, once per such tile.
    template <class F>
    void for_each_tile_cell(const world_grid& g, F&& f) const {
        for (std::size_t t = 0; t + 1 < bins_.offsets.size(); ++t) {
            std::uint64_t n = bins_.offsets[t + 1] - bins_.offsets[t];
            if (!n) continue;
            glm::ivec3 lo = bins_.tile_coord(int(t)) * io::detail::tile_edge;
            glm::ivec3 a = cell_of(lo, g.origin, g.chunk_bits), b = cell_of(lo + io::detail::tile_edge - 1, g.origin, g.chunk_bits);
            for (int z = a.z; z <= b.z; ++z)
                for (int y = a.y; y <= b.y; ++y)
                    for (int x = a.x; x <= b.x; ++x) f(glm::ivec3(x, y, z), n);
        }
    }

    const io::triangle_mesh* mesh_;
    int resolution_;
    io::voxel_grid_map map_;
    std::vector<glm::dvec3> vox_;
    io::detail::tile_bins bins_;
    palette palette_;
};

}  // namespace voxray
