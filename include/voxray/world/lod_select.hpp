// LOD selection (Aokana 3.4, after Virtual Voxel): down the implicit octree of chunks from
// the top LOD, a region is split into its 8 children while
//     LODError = ChunkSize * StreamingFactor - |ChunkCenter - Camera|  > 0
// (ChunkSize: the region's edge in world voxels), so regions near the camera get fine
// chunks and far ones coarse chunks; a larger factor keeps finer chunks farther away.
// Regions with no voxels at LOD 0 are skipped; a chosen region whose chunk has no voxels
// at that LOD (the density rule dropped them all) stays empty.
#pragma once
#include <cmath>
#include <set>
#include <vector>

#include <glm/glm.hpp>

#include "voxray/core/error.hpp"
#include "voxray/world/chunk_voxels.hpp"
#include "voxray/world/manifest.hpp"

namespace voxray {

struct lod_choice {
    chunk_key key;
    double distance = 0;  // from the camera to the chunk's centre, in world voxels
};

// Which regions hold LOD 0 chunks, per LOD: what selection walks.
class lod_tree {
public:
    explicit lod_tree(const world_manifest& m) : manifest_(&m), occupied_(std::size_t(m.grid.top_lod) + 1) {
        for (auto& c : m.chunks)
            if (c.key.lod == 0)
                for (int n = 0; n <= m.grid.top_lod; ++n) occupied_[std::size_t(n)].insert(c.key.cell >> n);
    }

    // The cut for a camera at `camera` (world voxels), coarse LODs first, then nearer first.
    std::vector<lod_choice> select(glm::dvec3 camera, double streaming_factor) const {
        if (!(streaming_factor > 0.0) || !std::isfinite(streaming_factor))
            fail("world: streaming factor ", streaming_factor, " must be a positive number");
        std::vector<lod_choice> out;
        int top = manifest_->grid.top_lod;
        for (auto& cell : occupied_[std::size_t(top)]) visit(top, cell, camera, streaming_factor, out);
        std::sort(out.begin(), out.end(), [](const lod_choice& a, const lod_choice& b) {
            return a.key.lod != b.key.lod ? a.key.lod > b.key.lod : a.distance < b.distance;
        });
        return out;
    }

    // The centre of a LOD n chunk's region in world coordinates.
    glm::dvec3 centre(const chunk_key& k) const {
        const world_grid& g = manifest_->grid;
        double edge = double(std::int64_t(g.edge()) << k.lod);
        return glm::dvec3(g.origin) + (glm::dvec3(k.cell) + 0.5) * edge;
    }

private:
    void visit(int lod, glm::ivec3 cell, glm::dvec3 camera, double factor, std::vector<lod_choice>& out) const {
        if (!occupied_[std::size_t(lod)].count(cell)) return;
        chunk_key key{lod, cell};
        double distance = glm::length(centre(key) - camera);
        double size = double(std::int64_t(manifest_->grid.edge()) << lod);
        if (lod > 0 && size * factor - distance > 0) {
            for (int o = 0; o < 8; ++o) visit(lod - 1, cell * 2 + glm::ivec3(o & 1, (o >> 1) & 1, o >> 2), camera, factor, out);
            return;
        }
        if (manifest_->find(key)) out.push_back({key, distance});
    }

    const world_manifest* manifest_;
    std::vector<std::set<glm::ivec3, ivec3_less>> occupied_;
};

}  // namespace voxray
