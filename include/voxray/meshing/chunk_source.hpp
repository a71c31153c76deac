// Where chunks come from. A source is anything with a
//
//   void read_box(const Source&, const box3i& box, std::uint8_t* out)
//
// found by argument-dependent lookup: it writes the material of every voxel of `box`
// (world coordinates) to `out`, x fastest, then y, then z, 0 where empty. fill_chunk() reads
// the chunk's interior and its one-voxel shell through it, so one function per structure
// gives the mesher all it needs.
#pragma once
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <vector>

#include "voxray/core/box.hpp"
#include "voxray/core/ivec3_less.hpp"
#include "voxray/meshing/chunk.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray {

// The voxel model: copies rows of its 16^3 chunks, so a 64^3 box costs 64 hash lookups
// and 16,384 copies of 16 bytes.
inline void read_box(const voxel_model& model, const box3i& box, std::uint8_t* out) {
    glm::ivec3 e = box.extent();
    std::fill(out, out + box.volume(), std::uint8_t(0));
    constexpr int edge = voxel_model::chunk_edge;
    glm::ivec3 first = box.min >> voxel_model::chunk_bits;
    glm::ivec3 last = (box.max - 1) >> voxel_model::chunk_bits;
    for (int cz = first.z; cz <= last.z; ++cz)
        for (int cy = first.y; cy <= last.y; ++cy)
            for (int cx = first.x; cx <= last.x; ++cx) {
                glm::ivec3 origin = glm::ivec3(cx, cy, cz) * edge;
                const voxel_model::chunk* c = model.find_chunk(origin);
                if (!c) continue;
                glm::ivec3 lo = glm::max(origin, box.min), hi = glm::min(origin + edge, box.max);
                for (int z = lo.z; z < hi.z; ++z)
                    for (int y = lo.y; y < hi.y; ++y) {
                        const std::uint8_t* src = c->voxels.data() + voxel_model::local_index({lo.x, y, z});
                        std::uint8_t* dst = out + (std::size_t(z - box.min.z) * e.y + std::size_t(y - box.min.y)) * e.x +
                                            std::size_t(lo.x - box.min.x);
                        std::memcpy(dst, src, std::size_t(hi.x - lo.x));
                    }
            }
}

namespace meshing {

// Origins of the 64^3 chunks that hold a voxel of the model, sorted (z, then y, then x).
inline std::vector<glm::ivec3> chunk_origins(const voxel_model& model) {
    std::vector<glm::ivec3> out;
    model.for_each_chunk([&](glm::ivec3 origin, const voxel_model::chunk&) { out.push_back(chunk_origin(chunk_of(origin))); });
    std::sort(out.begin(), out.end(), ivec3_less{});
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// Fills `chunk` with the 64^3 chunk at `origin` (a multiple of 64) of `source` and the
// solid shell around it. `scratch` holds the shell's slabs between calls.
template <class Source>
void fill_chunk(const Source& source, glm::ivec3 origin, chunk_voxels& chunk, std::vector<std::uint8_t>& scratch) {
    if (origin.x % chunk_edge || origin.y % chunk_edge || origin.z % chunk_edge)
        fail("mesh chunk origin (", origin.x, ", ", origin.y, ", ", origin.z, ") is not a multiple of ", chunk_edge);
    chunk.origin = origin;
    read_box(source, box3i{origin, origin + chunk_edge}, chunk.material.data());
    chunk.update_interior_rows();
    // The shell: two 66 x 66 slabs in z, two 66 x 64 in y, two 64 x 64 in x.
    const int n = chunk_edge;
    const box3i slabs[6] = {
        {{-1, -1, -1}, {n + 1, n + 1, 0}}, {{-1, -1, n}, {n + 1, n + 1, n + 1}},
        {{-1, -1, 0}, {n + 1, 0, n}},      {{-1, n, 0}, {n + 1, n + 1, n}},
        {{-1, 0, 0}, {0, n, n}},           {{n, 0, 0}, {n + 1, n, n}},
    };
    for (const box3i& local : slabs) {
        scratch.resize(local.volume());
        read_box(source, box3i{origin + local.min, origin + local.max}, scratch.data());
        std::size_t i = 0;
        for (int z = local.min.z; z < local.max.z; ++z)
            for (int y = local.min.y; y < local.max.y; ++y)
                for (int x = local.min.x; x < local.max.x; ++x) chunk.set_shell(x, y, z, scratch[i++] != 0);
    }
}

}  // namespace meshing
}  // namespace voxray
