// Chunk meshes kept in step with an editable source (brickmap, NAADF, or anything with a
// read_box): after edits, only the chunks whose quads may have changed are read and meshed
// again. A chunk's quads depend on its own voxels and on its one-voxel shell (faces culled
// across its sides, AO corners), so an edit inside a box changes the meshes of the chunks
// that the box, grown by one voxel on every side, meets.
#pragma once
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <map>
#include <span>
#include <vector>

#include "voxray/core/box.hpp"
#include "voxray/core/ivec3_less.hpp"
#include "voxray/meshing/chunk.hpp"
#include "voxray/meshing/chunk_mesh.hpp"
#include "voxray/meshing/chunk_source.hpp"
#include "voxray/meshing/mesher.hpp"

namespace voxray::meshing {

// Origins of the chunks whose meshes edits inside `edited` may change: sorted (z, y, x), unique.
inline std::vector<glm::ivec3> chunks_to_remesh(std::span<const box3i> edited) {
    std::vector<glm::ivec3> out;
    for (const box3i& b : edited) {
        if (b.empty()) continue;
        glm::ivec3 lo = chunk_of(b.min - 1), hi = chunk_of(b.max);  // b.max - 1 grown by one voxel
        for (int z = lo.z; z <= hi.z; ++z)
            for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x) out.push_back(chunk_origin({x, y, z}));
    }
    std::sort(out.begin(), out.end(), ivec3_less{});
    out.erase(std::unique(out.begin(), out.end()), out.end());
    return out;
}

// What one remesh() did.
struct remesh_stats {
    std::size_t chunks = 0;  // read and meshed again
    double seconds = 0;      // reading and meshing them
    double microseconds_per_chunk() const { return chunks ? seconds * 1e6 / double(chunks) : 0.0; }
};

// The meshes of a source's chunks by origin; chunks without quads are not kept.
class chunk_meshes {
public:
    explicit chunk_meshes(mesher_options options = {}) : mesher_(options) {}

    template <class Source>
    void mesh(const Source& source, std::span<const glm::ivec3> origins) {
        for (glm::ivec3 origin : origins) mesh_one(source, origin);
    }

    // After edits inside `edited` (the regions' bounds): the touched chunks again.
    template <class Source>
    remesh_stats remesh(const Source& source, std::span<const box3i> edited) {
        auto start = std::chrono::steady_clock::now();
        auto origins = chunks_to_remesh(edited);
        mesh(source, origins);
        return {origins.size(), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
    }

    const std::map<glm::ivec3, chunk_mesh, ivec3_less>& by_origin() const { return meshes_; }

private:
    template <class Source>
    void mesh_one(const Source& source, glm::ivec3 origin) {
        fill_chunk(source, origin, chunk_, scratch_);
        chunk_mesh m = mesher_.mesh(chunk_);
        if (m.words.empty()) meshes_.erase(origin);
        else meshes_[origin] = std::move(m);
    }

    mesher mesher_;
    chunk_voxels chunk_;
    std::vector<std::uint8_t> scratch_;
    std::map<glm::ivec3, chunk_mesh, ivec3_less> meshes_;
};

}  // namespace voxray::meshing
