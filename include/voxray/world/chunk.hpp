// One chunk of a chunked world: its place in the LOD octree, its solid box and its DAG.
// What the builder makes, the chunk files hold (world/chunk_file.hpp) and the world's
// blob places (world/world_blob.hpp).
#pragma once
#include <cstdint>
#include <tuple>

#include <glm/glm.hpp>

#include "voxray/core/blob.hpp"
#include "voxray/world/layout.h"

namespace voxray {

// A voxel of a chunk, (x, y, z) in [0, C), as one word (world/layout.h): the key of the
// builder's voxel lists and the directory's solid box corners.
inline std::uint32_t pack_chunk_voxel(glm::ivec3 p) {
    return VX_WD_BOX_PACK(std::uint32_t(p.x), std::uint32_t(p.y), std::uint32_t(p.z));
}
inline glm::ivec3 unpack_chunk_voxel(std::uint32_t w) { return {int(VX_WD_BOX_X(w)), int(VX_WD_BOX_Y(w)), int(VX_WD_BOX_Z(w))}; }

// A chunk's place: its LOD n and its coordinates in the grid of LOD n chunks (cell / 2^n).
struct chunk_key {
    int lod = 0;
    glm::ivec3 cell{0};
    bool operator==(const chunk_key&) const = default;
};

// The one order chunks are kept in (the manifest, the residency sets, the directory's
// slots): by (lod, z, y, x).
struct chunk_key_less {
    bool operator()(const chunk_key& a, const chunk_key& b) const {
        return std::tie(a.lod, a.cell.z, a.cell.y, a.cell.x) < std::tie(b.lod, b.cell.z, b.cell.y, b.cell.x);
    }
};

struct chunk_record {
    chunk_key key;
    int chunk_bits = 8;                        // C = 2^chunk_bits; the DAG's depth
    glm::ivec3 solid_min{0}, solid_max{-1};    // inclusive box of solid voxels in the chunk's own voxels [0, C); empty when max < min
    std::uint64_t voxel_count = 0;             // solid voxels (the DAG header's count)
    std::uint32_t source_hash = 0;             // the build's options and input, checked when a build resumes
    blob_words dag;                            // a svdag blob (svdag/layout.h) over the cube [0, C)^3

    bool empty() const { return voxel_count == 0; }
};

}  // namespace voxray
