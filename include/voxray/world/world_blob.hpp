// The chunked world's grid, and its blob (world/layout.h) for a given cut: which chunk,
// of which LOD, stands for each cell.
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <map>
#include <set>
#include <span>
#include <vector>

#include "voxray/core/blob.hpp"
#include "voxray/core/box.hpp"
#include "voxray/core/error.hpp"
#include "voxray/svdag/builder.hpp"
#include "voxray/world/chunk.hpp"
#include "voxray/world/layout.h"

namespace voxray {

// The grid of cells (LOD 0 chunk regions, C = 2^chunk_bits voxels a side). top_lod is the
// first LOD at which at most 2 chunks a side cover the world; the origin is a multiple of
// C * 2^top_lod, so a chunk's key does not depend on how far the world reaches.
struct world_grid {
    glm::ivec3 origin{0};  // world position of cell (0,0,0)'s min corner
    glm::ivec3 cells{1};   // per axis
    int chunk_bits = 8;
    int top_lod = 0;

    int edge() const { return 1 << chunk_bits; }
    // The key of the LOD n chunk holding cell c.
    static chunk_key key_of(glm::ivec3 c, int lod) { return {lod, c >> lod}; }

    static world_grid fit(box3i bounds, int chunk_bits) {
        if (chunk_bits < VX_WD_MIN_CHUNK_BITS || chunk_bits > VX_WD_MAX_CHUNK_BITS)
            fail("world: chunk_bits ", chunk_bits, " is outside [", VX_WD_MIN_CHUNK_BITS, ", ", VX_WD_MAX_CHUNK_BITS, "]");
        world_grid g;
        g.chunk_bits = chunk_bits;
        if (bounds.empty()) return g;
        auto floor_div = [](int a, std::int64_t b) { return std::int64_t(a >= 0 ? a / b : -((b - 1 - a) / b)); };
        for (int n = 0;; ++n) {
            std::int64_t region = std::int64_t(1) << (chunk_bits + n);
            bool fits = true;
            for (int a = 0; a < 3; ++a) fits = fits && floor_div(bounds.max[a] - 1, region) - floor_div(bounds.min[a], region) <= 1;
            if (fits || n == VX_WD_MAX_LOD) {
                g.top_lod = n;
                for (int a = 0; a < 3; ++a) {
                    g.origin[a] = int(floor_div(bounds.min[a], region) * region);
                    g.cells[a] = int((std::int64_t(bounds.max[a]) - g.origin[a] + g.edge() - 1) >> chunk_bits);
                }
                return g;
            }
        }
    }
};

// A chunk standing for the cells of its region (chunk null or empty: the region has no
// voxels at that LOD).
struct placement {
    chunk_key key;
    const chunk_record* chunk = nullptr;
};

namespace world_pack {

// The directory while it is built: nodes of 8 slots, each empty, a node or an entry
// (a placement, whose region is the slot's).
struct slot {
    enum kind_t : std::uint8_t { empty, node, entry } kind = empty;
    std::uint32_t index = 0;  // into nodes or entries
};
using node = std::array<slot, 8>;

struct directory {
    std::vector<node> nodes{node{}};  // nodes[0]: the root
    std::vector<placement> entries;

    // Sets the slot of p's region, splitting coarser entries on the way into 8 copies.
    void insert(const placement& p, int root_level) {
        std::uint32_t at = 0;
        glm::ivec3 c = p.key.cell << p.key.lod;  // the region's first cell
        for (int level = root_level; level > p.key.lod; --level) {
            glm::ivec3 b = (c >> (level - 1)) & 1;
            slot& s = nodes[at][std::size_t(b.x | (b.y << 1) | (b.z << 2))];
            if (level - 1 == p.key.lod) {
                bool solid = p.chunk && !p.chunk->empty();
                if (solid) entries.push_back(p);
                s = solid ? slot{slot::entry, std::uint32_t(entries.size() - 1)} : slot{};
                return;
            }
            if (s.kind != slot::node) {
                node split;
                split.fill(s);  // an entry's parts, or nothing
                nodes.push_back(split);
                // `s` may dangle after push_back: index again.
                nodes[at][std::size_t(b.x | (b.y << 1) | (b.z << 2))] = slot{slot::node, std::uint32_t(nodes.size() - 1)};
            }
            at = nodes[at][std::size_t(b.x | (b.y << 1) | (b.z << 2))].index;
        }
    }
    // Nodes whose slots are all empty become empty slots (a ray leaves them in one move).
    slot collapse(slot s) {
        if (s.kind != slot::node) return s;
        bool any = false;
        for (auto& child : nodes[s.index]) child = collapse(child), any = any || child.kind != slot::empty;
        return any ? s : slot{};
    }
};

}  // namespace world_pack

// The header and directory words of a cut, for DAGs placed wherever the caller puts
// them (after the directory in one blob, pack_world; or in a pool, world/stream/streamed_world.hpp).
// `cut` is applied coarse to fine, so a finer chunk stands for its cells where a coarser
// one covers them too (a chunk not resident is traced at the finest resident LOD above it,
// when the caller passes the resident ones). Cells no placement covers have no voxels.
class world_directory {
public:
    world_directory(const world_grid& g, std::span<const placement> cut, svdag_attributes attributes)
        : grid_(g), kind_(attributes == svdag_attributes::exact ? VX_SV_ATTRIBUTES_EXACT : VX_SV_ATTRIBUTES_COLOUR_BLOCKS) {
        std::vector<placement> order(cut.begin(), cut.end());
        std::stable_sort(order.begin(), order.end(), [](const placement& a, const placement& b) { return a.key.lod > b.key.lod; });
        for (auto& p : order) {
            if (p.key.lod < 0 || p.key.lod > g.top_lod)
                fail("world: a chunk of LOD ", p.key.lod, " in a world whose LODs are 0..", g.top_lod);
            if (p.chunk && !p.chunk->empty()) {
                if (p.chunk->chunk_bits != g.chunk_bits)
                    fail("world: a chunk of 2^", p.chunk->chunk_bits, " voxels a side in a world of 2^", g.chunk_bits, " chunks");
                if (p.chunk->dag.size() <= VX_SV_HEADER_WORDS || p.chunk->dag[VX_SV_HEADER_ATTRIBUTE_KIND] != kind_)
                    fail("world: chunk (LOD ", p.key.lod, ", ", p.key.cell.x, " ", p.key.cell.y, " ", p.key.cell.z,
                         ") has other attributes than its world");
            }
            dir_.insert(p, g.top_lod + 1);
        }
        for (auto& s : dir_.nodes[0]) s = dir_.collapse(s);
        // Word offsets: the header, the nodes reachable from the root (breadth first), entries.
        node_at_.assign(dir_.nodes.size(), -1);
        words_ = VX_WD_HEADER_WORDS;
        std::vector<std::uint32_t> reach{0};
        for (std::size_t i = 0; i < reach.size(); ++i) {
            node_at_[reach[i]] = std::int64_t(words_);
            words_ += VX_WD_NODE_WORDS;
            for (auto& s : dir_.nodes[reach[i]])
                if (s.kind == world_pack::slot::node) reach.push_back(s.index);
        }
        entries_at_ = words_;
        words_ += VX_WD_ENTRY_WORDS * dir_.entries.size();
        table_at_ = words_;
        words_ += VX_WD_ROW_WORDS * dir_.entries.size();
    }

    // Header and directory words.
    std::uint64_t words() const { return words_; }
    // The chunks the directory refers to, once each, in entry order.
    std::vector<const chunk_record*> chunks() const {
        std::vector<const chunk_record*> out;
        std::set<const chunk_record*> seen;
        for (auto& e : dir_.entries)
            if (seen.insert(e.chunk).second) out.push_back(e.chunk);
        return out;
    }

    // Writes words [0, words()) of the blob; dag_at(chunk) is where the chunk's DAG lies.
    template <class DagAt>
    void write(std::span<std::uint32_t> w, DagAt&& dag_at) const {
        // The walk covers the shown chunks' solid boxes (a coarse voxel may reach past the
        // finest data's bounds), and starts at their min corner, as the reference's does.
        box3i bounds;
        std::vector<box3i> boxes;  // each entry's solid box, world voxels
        for (auto& e : dir_.entries) {
            const chunk_record& c = *e.chunk;
            glm::ivec3 base = grid_.origin + ((e.key.cell << e.key.lod) << grid_.chunk_bits);
            boxes.push_back({base + (c.solid_min << e.key.lod), base + ((c.solid_max + 1) << e.key.lod)});
            bounds.include(boxes.back().min);
            bounds.include(boxes.back().max - 1);
        }
        glm::ivec3 extent = bounds.extent();
        glm::ivec3 start = bounds.empty() ? grid_.origin : bounds.min;
        std::fill(w.begin(), w.begin() + std::ptrdiff_t(words_), 0u);
        w[VX_WD_HEADER_MAGIC] = VX_WD_MAGIC;
        w[VX_WD_HEADER_VERSION] = VX_WD_VERSION;
        for (int a = 0; a < 3; ++a) {
            w[VX_WD_HEADER_ORIGIN + a] = std::uint32_t(start[a]);
            w[VX_WD_HEADER_EXTENT + a] = std::uint32_t(extent[a]);
            w[VX_WD_HEADER_SHIFT + a] = std::uint32_t(start[a] - grid_.origin[a]);
        }
        w[VX_WD_HEADER_CHUNK_BITS] = std::uint32_t(grid_.chunk_bits);
        w[VX_WD_HEADER_ROOT_LEVEL] = std::uint32_t(grid_.top_lod + 1);
        w[VX_WD_HEADER_ROOT] = VX_WD_HEADER_WORDS;
        w[VX_WD_HEADER_ATTRIBUTE_KIND] = kind_;
        w[VX_WD_HEADER_TABLE] = std::uint32_t(table_at_);
        w[VX_WD_HEADER_TABLE_ROWS] = std::uint32_t(dir_.entries.size());
        for (std::size_t n = 0; n < dir_.nodes.size(); ++n) {
            if (node_at_[n] < 0) continue;
            for (std::size_t o = 0; o < 8; ++o) {
                const auto& s = dir_.nodes[n][o];
                std::uint64_t child = s.kind == world_pack::slot::node ? std::uint64_t(node_at_[s.index])
                                      : s.kind == world_pack::slot::entry
                                          ? (entries_at_ + VX_WD_ENTRY_WORDS * s.index) | VX_WD_CHILD_IS_ENTRY
                                          : 0u;
                w[std::size_t(node_at_[n]) + o] = std::uint32_t(child);
            }
        }
        for (std::size_t i = 0; i < dir_.entries.size(); ++i) {
            const chunk_record& c = *dir_.entries[i].chunk;
            std::uint64_t e = entries_at_ + VX_WD_ENTRY_WORDS * i;
            w[e + VX_WD_ENTRY_DAG] = std::uint32_t(dag_at(&c));
            w[e + VX_WD_ENTRY_LOD] = std::uint32_t(dir_.entries[i].key.lod);
            w[e + VX_WD_ENTRY_BOX_MIN] = pack_chunk_voxel(c.solid_min);
            w[e + VX_WD_ENTRY_BOX_MAX] = pack_chunk_voxel(c.solid_max);
            std::uint64_t row = table_at_ + VX_WD_ROW_WORDS * i;
            w[row + VX_WD_ROW_ENTRY] = std::uint32_t(e) | VX_WD_CHILD_IS_ENTRY;
            for (int a = 0; a < 3; ++a) {
                w[row + VX_WD_ROW_MIN + a] = std::uint32_t(boxes[i].min[a] - start[a]);
                w[row + VX_WD_ROW_MAX + a] = std::uint32_t(boxes[i].max[a] - start[a]);
            }
            w[row + VX_WD_ROW_LOD] = std::uint32_t(dir_.entries[i].key.lod);
        }
    }

private:
    world_grid grid_;
    std::uint32_t kind_;
    world_pack::directory dir_;
    std::vector<std::int64_t> node_at_;
    std::uint64_t words_ = 0, entries_at_ = 0, table_at_ = 0;
};

// The whole blob of a cut: header, directory, then each chunk's DAG once.
inline blob_words pack_world(const world_grid& g, std::span<const placement> cut, svdag_attributes attributes) {
    world_directory dir(g, cut, attributes);
    std::map<const chunk_record*, std::uint64_t> placed;
    std::uint64_t words = dir.words();
    for (auto* c : dir.chunks()) placed[c] = words, words += c->dag.size();
    check_blob_size("world", words);
    blob_words w(words, 0u);
    dir.write(w, [&](const chunk_record* c) { return placed.at(c); });
    for (auto& [chunk, at] : placed) std::copy(chunk->dag.begin(), chunk->dag.end(), w.begin() + std::ptrdiff_t(at));
    return w;
}

}  // namespace voxray
