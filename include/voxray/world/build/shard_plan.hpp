// How a world build is cut into shares for many processes (batch jobs, MPI ranks).
//
// A share is a set of *units*: the subtrees under the cells of one LOD, the split LOD S.
// A unit's chunks of LODs 0..S depend on nothing outside it (LOD n is made from the 8
// chunks below it), so a process builds its units from the source up to LOD S alone,
// without waiting for any other; the finishing step builds the few chunks above S and the
// manifest. S is the highest LOD that still has at least 8 units per share (or every
// cell its own unit, when the world has fewer cells), so that shares can be balanced.
//
// Shares are balanced by the source's estimate of each LOD-0 cell's work (a model's
// voxels, a mesh's triangles; one per cell when the source has no estimate): the units,
// in z-y-x order, are cut into N runs of about equal work, so a share stays in one
// region of the world.
#pragma once
#include <algorithm>
#include <cstdint>
#include <map>
#include <set>
#include <vector>

#include <glm/vec3.hpp>

#include "voxray/core/error.hpp"
#include "voxray/core/ivec3_less.hpp"
#include "voxray/world/world_blob.hpp"

namespace voxray {

// Share `index` of `count` (index in [0, count)): the --shard K/N of the tool.
struct world_shard {
    unsigned index = 0, count = 1;
};

// A source may estimate the work of its LOD-0 cells:
//   std::vector<std::uint64_t> cell_work(const world_grid&, const std::vector<glm::ivec3>& cells) const;
template <class Source>
std::vector<std::uint64_t> cell_work(const Source& source, const world_grid& g, const std::vector<glm::ivec3>& cells) {
    if constexpr (requires { source.cell_work(g, cells); }) {
        auto work = source.cell_work(g, cells);
        if (work.size() != cells.size()) fail("world build: the source estimated ", work.size(), " cells of ", cells.size());
        return work;
    } else {
        return std::vector<std::uint64_t>(cells.size(), 1);
    }
}

struct build_unit {
    std::vector<glm::ivec3> cells;   // its LOD-0 cells, sorted
    std::uint64_t work = 0;
};

struct shard_split {
    int split_lod = 0;
    std::vector<build_unit> units;   // sorted by cell (z-y-x)

    // The highest LOD with at least min(cells, 8 * shards) units. `cells` sorted.
    static int choose_split_lod(const std::vector<glm::ivec3>& cells, int top_lod, unsigned shards) {
        std::size_t want = std::min<std::size_t>(cells.size(), std::size_t(8) * shards);
        for (int lod = top_lod; lod > 0; --lod) {
            std::set<glm::ivec3, ivec3_less> units;
            for (auto& c : cells) units.insert(c >> lod);
            if (units.size() >= want) return lod;
        }
        return 0;
    }

    static shard_split make(const std::vector<glm::ivec3>& cells, const std::vector<std::uint64_t>& work, int top_lod,
                            unsigned shards) {
        shard_split s;
        s.split_lod = choose_split_lod(cells, top_lod, shards);
        std::map<glm::ivec3, build_unit, ivec3_less> by_cell;
        for (std::size_t i = 0; i < cells.size(); ++i) {
            build_unit& u = by_cell[cells[i] >> s.split_lod];
            u.cells.push_back(cells[i]);
            u.work += std::max<std::uint64_t>(work[i], 1);
        }
        for (auto& [cell, unit] : by_cell) s.units.push_back(std::move(unit));  // in the map's z-y-x order
        return s;
    }

    // The units of share `index` of `count`: the run of units whose middle of work falls
    // in [index, index + 1) * total / count.
    std::vector<std::size_t> share(unsigned index, unsigned count) const {
        std::uint64_t total = 0;
        for (auto& u : units) total += u.work;
        std::vector<std::size_t> out;
        std::uint64_t before = 0;
        for (std::size_t i = 0; i < units.size(); ++i) {
            // (before + work / 2) * count / total, exactly: in integers, every process agrees
            auto owner = unsigned((unsigned __int128)(2 * before + units[i].work) * count / (2 * (unsigned __int128)total));
            if (owner >= count) owner = count - 1;
            if (owner == index) out.push_back(i);
            before += units[i].work;
        }
        return out;
    }
};

}  // namespace voxray
