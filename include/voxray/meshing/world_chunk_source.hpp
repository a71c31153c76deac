// A shown chunk of an open world (world/chunk.hpp: a DAG over C^3 cells at LOD n, each cell
// 2^n world voxels) as a source of mesh chunks: its cells decoded once into bytes, read by
// fill_chunk through read_box like any structure, in the chunk's own cell coordinates
// [0, C)^3. Cells outside the chunk read as empty, so faces on the chunk's sides are always
// made: neighbouring chunks may stand at other LODs. clear() cuts out the cells a finer
// shown chunk covers.
//
//   meshing::world_chunk_source source(record, [&](std::uint32_t value) { return material_of(value); });
//   for (glm::ivec3 o : source.mesh_origins()) { fill_chunk(source, o, chunk, scratch); mesher.mesh(chunk, m); }
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include <glm/vec3.hpp>

#include "voxray/core/box.hpp"
#include "voxray/meshing/chunk.hpp"
#include "voxray/svdag/decode.hpp"
#include "voxray/world/chunk.hpp"

namespace voxray::meshing {

class world_chunk_source {
public:
    // `material(value)`: a cell's material byte (1..255) from its DAG attribute (a palette
    // index in exact worlds, an RGBA8 colour in colour worlds).
    template <class Material>
    world_chunk_source(const chunk_record& record, Material&& material) : edge_(1 << record.chunk_bits) {
        cells_.assign(std::size_t(edge_) * std::size_t(edge_) * std::size_t(edge_), 0);
        if (record.empty()) return;
        for (const decoded_voxel& v : decode_svdag(record.dag)) {
            std::uint8_t m = material(v.attribute);
            cells_[index(v.position)] = m ? m : 1;  // solid stays solid
        }
    }

    int edge() const { return edge_; }

    // Empties the cells of `box` (cell coordinates, clipped to the chunk): where a finer
    // chunk of the world is shown, a coarser stand-in must not draw as well.
    void clear(const box3i& box) {
        glm::ivec3 lo = glm::max(box.min, glm::ivec3(0)), hi = glm::min(box.max, glm::ivec3(edge_));
        for (int z = lo.z; z < hi.z; ++z)
            for (int y = lo.y; y < hi.y; ++y)
                for (int x = lo.x; x < hi.x; ++x) cells_[index({x, y, z})] = 0;
    }

    // The 64-aligned origins, in cell coordinates, of the mesh chunks that hold a cell (one
    // for a world chunk smaller than a mesh chunk).
    std::vector<glm::ivec3> mesh_origins() const {
        std::vector<glm::ivec3> out;
        int n = (edge_ + chunk_edge - 1) / chunk_edge;
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    glm::ivec3 o = glm::ivec3(x, y, z) * chunk_edge;
                    if (any_solid(o)) out.push_back(o);
                }
        return out;
    }

    friend void read_box(const world_chunk_source& s, const box3i& box, std::uint8_t* out) {
        glm::ivec3 e = box.extent();
        std::memset(out, 0, std::size_t(e.x) * std::size_t(e.y) * std::size_t(e.z));
        glm::ivec3 lo = glm::max(box.min, glm::ivec3(0)), hi = glm::min(box.max, glm::ivec3(s.edge_));
        if (glm::any(glm::greaterThanEqual(lo, hi))) return;
        for (int z = lo.z; z < hi.z; ++z)
            for (int y = lo.y; y < hi.y; ++y)
                std::memcpy(out + (std::size_t(z - box.min.z) * std::size_t(e.y) + std::size_t(y - box.min.y)) *
                                      std::size_t(e.x) + std::size_t(lo.x - box.min.x),
                            &s.cells_[s.index({lo.x, y, z})], std::size_t(hi.x - lo.x));
    }

private:
    std::size_t index(glm::ivec3 p) const {
        return (std::size_t(p.z) * std::size_t(edge_) + std::size_t(p.y)) * std::size_t(edge_) + std::size_t(p.x);
    }

    bool any_solid(glm::ivec3 o) const {
        int span = std::min(chunk_edge, edge_);
        for (int z = o.z; z < o.z + span; ++z)
            for (int y = o.y; y < o.y + span; ++y) {
                const std::uint8_t* row = &cells_[index({o.x, y, z})];
                if (std::any_of(row, row + span, [](std::uint8_t c) { return c != 0; })) return true;
            }
        return false;
    }

    int edge_;
    std::vector<std::uint8_t> cells_;  // x fastest; 0 = empty
};

}  // namespace voxray::meshing
