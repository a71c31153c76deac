// Builds the sparse voxel DAG's blob (svdag/layout.h) from a voxel model:
//   1. the model's 16^3 chunks, sorted in Morton order, are cut into 4^3 leaf masks and
//      the payload bytes of their solid voxels in depth-first order (in parallel, each
//      thread a contiguous run of chunks, so concatenating keeps the order);
//   2. level by level from the leaves up, identical nodes are merged (level_dedup.hpp,
//      parallel and deterministic) and the merged children make the parents' items;
//   3. the distinct nodes are laid out root first, level by level, each level's nodes in
//      id order, and the attributes after them.
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <utility>
#include <vector>

#include "voxray/core/blob.hpp"
#include "voxray/core/box.hpp"
#include "voxray/core/error.hpp"
#include "voxray/model/build_threads.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/svdag/colour_blocks.hpp"
#include "voxray/svdag/layout.h"
#include "voxray/svdag/level_dedup.hpp"
#include "voxray/svdag/morton.hpp"

namespace voxray {

enum class svdag_attributes { exact, colour_blocks };

struct svdag_options {
    svdag_attributes attributes = svdag_attributes::exact;
    float colour_error = 0.05f;     // colour blocks: the largest channel error in a block, colours in [0, 1]
    unsigned threads = 0;           // build threads; 0: all hardware threads
    std::uint64_t max_blob_bytes = std::uint64_t(4) << 30;
};

struct svdag_stats {
    int depth = 0;                       // the cube is 2^depth voxels a side
    std::uint64_t octree_nodes = 0;      // nodes (leaves included) before merging
    std::uint64_t dag_nodes = 0;         // distinct nodes stored
    std::uint64_t geometry_bytes = 0;    // header and nodes
    std::uint64_t attribute_bytes = 0;   // payload bytes or colour blocks
    std::uint64_t colour_blocks = 0;
    double colour_error_max = 0, colour_error_mean = 0;  // colour blocks against the exact colours
    double dedup_ratio() const { return dag_nodes ? double(octree_nodes) / double(dag_nodes) : 1.0; }
    // The figures `voxray info` and `voxray bench` report beside every structure's size.
    std::vector<std::pair<const char*, double>> figures() const {
        std::vector<std::pair<const char*, double>> f = {
            {"depth", depth},
            {"geometry_bytes", double(geometry_bytes)},
            {"attribute_bytes", double(attribute_bytes)},
            {"octree_nodes", double(octree_nodes)},
            {"dag_nodes", double(dag_nodes)},
            {"dedup_ratio", dedup_ratio()}};
        if (colour_blocks) {
            f.push_back({"colour_blocks", double(colour_blocks)});
            f.push_back({"colour_error_max", colour_error_max});
            f.push_back({"colour_error_mean", colour_error_mean});
        }
        return f;
    }
};

namespace svdag_build {

struct interior {
    std::uint32_t mask = 0;
    std::array<std::uint32_t, 8> child{};  // child ids on the level below, by octant (0 where absent)
    bool operator==(const interior&) const = default;
};

// One level's items in depth-first order: their Morton keys and the ids of their contents.
struct level_items {
    std::vector<std::uint64_t> keys;
    std::vector<std::uint32_t> ids;
};

// The leaves of a DAG in depth-first (Morton) order: each one's Morton key (of its 4^3
// brick's coordinates in the cube), its 64-bit mask, and the attributes of the solid
// voxels in depth-first order: payload bytes, or (colour blocks built from colours rather
// than palette indices) RGBA8 colours.
struct leaf_scan {
    std::vector<std::uint64_t> keys, masks;
    std::vector<std::uint8_t> payload;
    std::vector<std::uint32_t> colours;
};

// Where a DAG's cube lies: its depth D, and the header's origin, extent and shift
// (svdag/layout.h). The leaves' keys are relative to the cube.
struct dag_frame {
    glm::ivec3 origin{0}, extent{0}, shift{0};
    int depth = VX_SV_MIN_DEPTH;
};

// The leaves and depth-first payload of the chunks [begin, end) (sorted by Morton key).
inline void scan_chunks(std::span<const std::pair<std::uint64_t, const voxel_model::chunk*>> chunks, leaf_scan& out) {
    for (auto& [key, c] : chunks) {
        for (std::uint32_t m = 0; m < 64; ++m) {
            // Leaf (lx, ly, lz) of the chunk from its 6-bit Morton code.
            int lx = int((m & 1) | ((m >> 2) & 2)), ly = int(((m >> 1) & 1) | ((m >> 3) & 2)),
                lz = int(((m >> 2) & 1) | ((m >> 4) & 2));
            std::uint64_t mask = 0;
            for (int z = 0; z < 4; ++z)
                for (int y = 0; y < 4; ++y)
                    for (int x = 0; x < 4; ++x) {
                        std::uint8_t v = c->voxels[voxel_model::local_index({lx * 4 + x, ly * 4 + y, lz * 4 + z})];
                        if (!v) continue;
                        mask |= std::uint64_t(1) << (x | (y << 2) | (z << 4));
                        out.payload.push_back(v);
                    }
            if (!mask) continue;
            out.keys.push_back((key << 6) | m);
            out.masks.push_back(mask);
        }
    }
}

inline int floor_div16(int a) { return a >= 0 ? a / 16 : -((15 - a) / 16); }

struct built {
    blob_words words;
    svdag_stats stats;
};

// Steps 2 and 3: merges the leaves into the DAG and lays out its blob. `pal` maps payload
// bytes to colours for colour blocks (unused when the leaves carry colours).
inline built assemble(leaf_scan leaves, const dag_frame& frame, const svdag_options& options, const palette* pal) {
    if (options.attributes == svdag_attributes::colour_blocks && !(options.colour_error >= 0.0f && options.colour_error <= 1.0f))
        fail("svdag: colour_error ", options.colour_error, " is outside [0, 1] (a channel difference, colours in [0, 1])");
    if (leaves.keys.size() >= UINT32_MAX) fail("svdag: ", leaves.keys.size(), " leaves, above the limit of 2^32");
    built result;
    svdag_stats& stats = result.stats;
    int depth = frame.depth;
    stats.depth = depth;
    // 2. Merge level by level: leaves (depth D - 2), then interior levels up to the root.
    int leaf_depth = depth - VX_SV_LEAF_EDGE_BITS;
    auto merged_leaves = dedup_level(leaves.masks, options.threads, [](std::uint64_t m) { return mix64(m); },
                                     [](std::uint64_t a, std::uint64_t b) { return a == b; });
    std::vector<std::uint64_t> leaf_masks(merged_leaves.first.size());
    for (std::size_t u = 0; u < leaf_masks.size(); ++u) leaf_masks[u] = leaves.masks[merged_leaves.first[u]];
    std::vector<std::uint64_t> child_counts(leaf_masks.size());
    for (std::size_t u = 0; u < leaf_masks.size(); ++u) child_counts[u] = std::uint64_t(std::popcount(leaf_masks[u]));
    stats.octree_nodes = leaves.keys.size();
    stats.dag_nodes = leaf_masks.size();

    level_items below{std::move(leaves.keys), std::move(merged_leaves.id)};
    auto nodes = std::vector<std::vector<interior>>(std::size_t(leaf_depth));   // distinct nodes per depth
    auto counts = std::vector<std::vector<std::uint64_t>>(std::size_t(leaf_depth));
    for (int d = leaf_depth - 1; d >= 0; --d) {
        std::vector<interior> items;
        std::vector<std::uint64_t> keys;
        for (std::size_t i = 0; i < below.keys.size(); ++i) {
            std::uint64_t parent = below.keys[i] >> 3;
            if (keys.empty() || keys.back() != parent) keys.push_back(parent), items.emplace_back();
            auto octant = unsigned(below.keys[i] & 7);
            items.back().mask |= 1u << octant;
            items.back().child[octant] = below.ids[i];
        }
        if (items.empty() && d == 0) items.emplace_back(), keys.push_back(0);  // an empty world: a root with no children
        auto merged = dedup_level(
            items, options.threads,
            [](const interior& n) {
                std::uint64_t h = mix64(n.mask);
                for (auto c : n.child) h = mix64(h ^ c);
                return h;
            },
            [](const interior& a, const interior& b) { return a == b; });
        auto& level = nodes[std::size_t(d)];
        auto& level_counts = counts[std::size_t(d)];
        level.resize(merged.first.size());
        level_counts.resize(merged.first.size());
        for (std::size_t u = 0; u < level.size(); ++u) {
            level[u] = items[merged.first[u]];
            std::uint64_t n = 0;
            for (unsigned o = 0; o < 8; ++o)
                if (level[u].mask >> o & 1u) n += child_counts[level[u].child[o]];
            level_counts[u] = n;
        }
        stats.octree_nodes += items.size();
        stats.dag_nodes += level.size();
        child_counts = level_counts;
        below = {std::move(keys), std::move(merged.id)};
    }

    // 3. Addresses: root first, then each level's distinct nodes, then the leaves.
    auto address = std::vector<std::vector<std::uint64_t>>(std::size_t(leaf_depth) + 1);
    std::uint64_t cursor = VX_SV_HEADER_WORDS;
    for (int d = 0; d < leaf_depth; ++d)
        for (auto& n : nodes[std::size_t(d)]) {
            address[std::size_t(d)].push_back(cursor);
            cursor += VX_SV_NODE_WORDS(std::uint64_t(std::popcount(n.mask)));
        }
    for (std::size_t u = 0; u < leaf_masks.size(); ++u) {
        address[std::size_t(leaf_depth)].push_back(cursor);
        cursor += VX_SV_LEAF_WORDS;
    }
    std::uint64_t node_end = cursor;

    colour_blocks blocks;
    std::uint64_t attribute_words = 0;
    if (options.attributes == svdag_attributes::exact) {
        attribute_words = (leaves.payload.size() + 3) / 4;
    } else if (!leaves.colours.empty() || leaves.payload.empty()) {
        blocks = encode_colour_blocks(leaves.colours, options.colour_error);
    } else {
        blocks = encode_colour_blocks(leaves.payload, *pal, options.colour_error);
    }
    if (options.attributes == svdag_attributes::colour_blocks) attribute_words = 2 * std::uint64_t(blocks.starts.size());
    std::uint64_t total = node_end + attribute_words;
    if (total * 4 > options.max_blob_bytes)
        fail("svdag: the blob would be ", total * 4, " bytes (", node_end * 4, " of geometry, ", attribute_words * 4,
             " of attributes), above max_blob_bytes = ", options.max_blob_bytes);
    check_blob_size("svdag", total);

    blob_words& w = result.words;
    w.assign(total, 0u);
    w[VX_SV_HEADER_MAGIC] = VX_SV_MAGIC;
    w[VX_SV_HEADER_VERSION] = VX_SV_VERSION;
    for (int a = 0; a < 3; ++a) {
        w[VX_SV_HEADER_ORIGIN + a] = std::uint32_t(frame.origin[a]);
        w[VX_SV_HEADER_EXTENT + a] = std::uint32_t(frame.extent[a]);
        w[VX_SV_HEADER_SHIFT + a] = std::uint32_t(frame.shift[a]);
    }
    w[VX_SV_HEADER_DEPTH] = std::uint32_t(depth);
    w[VX_SV_HEADER_ROOT] = VX_SV_HEADER_WORDS;
    w[VX_SV_HEADER_NODE_WORDS] = std::uint32_t(node_end - VX_SV_HEADER_WORDS);
    w[VX_SV_HEADER_ATTRIBUTES] = std::uint32_t(node_end);
    w[VX_SV_HEADER_VOXELS] = std::uint32_t(counts[0][0]);  // the root's
    for (int d = 0; d < leaf_depth; ++d) {
        auto& child_address = address[std::size_t(d) + 1];
        // The children's counts: the level below's, or the leaves' popcounts.
        auto child_count = [&](std::uint32_t child) {
            return d + 1 < leaf_depth ? counts[std::size_t(d) + 1][child]
                                      : std::uint64_t(std::popcount(leaf_masks[child]));
        };
        for (std::size_t u = 0; u < nodes[std::size_t(d)].size(); ++u) {
            const interior& n = nodes[std::size_t(d)][u];
            std::uint64_t at = address[std::size_t(d)][u];
            const unsigned children = unsigned(std::popcount(n.mask));
            w[at] = n.mask;
            std::uint64_t below = 0;
            for (unsigned o = 0, k = 0; o < 8; ++o) {
                if (!(n.mask >> o & 1u)) continue;
                if (k > 0) w[at + VX_SV_NODE_BELOW(children, k)] = std::uint32_t(below);
                w[at + VX_SV_NODE_CHILDREN + k++] = std::uint32_t(child_address[n.child[o]]);
                below += child_count(n.child[o]);
            }
        }
    }
    for (std::size_t u = 0; u < leaf_masks.size(); ++u) {
        std::uint64_t at = address[std::size_t(leaf_depth)][u];
        w[at] = std::uint32_t(leaf_masks[u]);
        w[at + 1] = std::uint32_t(leaf_masks[u] >> 32);
    }
    if (options.attributes == svdag_attributes::exact) {
        w[VX_SV_HEADER_ATTRIBUTE_KIND] = VX_SV_ATTRIBUTES_EXACT;
        w[VX_SV_HEADER_ATTRIBUTE_COUNT] = std::uint32_t(leaves.payload.size());
        for (std::size_t i = 0; i < leaves.payload.size(); ++i)
            w[node_end + VX_SV_ATTRIBUTE_WORD(i)] |= std::uint32_t(leaves.payload[i]) << VX_SV_ATTRIBUTE_SHIFT(i);
    } else {
        std::uint64_t n = blocks.starts.size();
        w[VX_SV_HEADER_ATTRIBUTE_KIND] = VX_SV_ATTRIBUTES_COLOUR_BLOCKS;
        w[VX_SV_HEADER_ATTRIBUTE_COUNT] = std::uint32_t(n);
        w[VX_SV_HEADER_COLOURS] = std::uint32_t(node_end + n);
        w[VX_SV_HEADER_SEARCH_TOP] = n ? std::uint32_t(std::bit_floor(n)) : 0u;
        std::copy(blocks.starts.begin(), blocks.starts.end(), w.begin() + std::ptrdiff_t(node_end));
        std::copy(blocks.colours.begin(), blocks.colours.end(), w.begin() + std::ptrdiff_t(node_end + n));
        stats.colour_blocks = n;
        stats.colour_error_max = blocks.max_error;
        stats.colour_error_mean = blocks.mean_error;
    }
    stats.geometry_bytes = node_end * 4;
    stats.attribute_bytes = attribute_words * 4;
    return result;
}

// Step 1 for a voxel model (the cube fitted to its bounds), then assemble.
inline built build(const voxel_model& model, const svdag_options& options) {
    box3i bounds = model.bounds();
    glm::ivec3 extent = bounds.empty() ? glm::ivec3(0) : bounds.extent();
    glm::ivec3 cube_origin = bounds.empty() ? glm::ivec3(0)
                                            : glm::ivec3(floor_div16(bounds.min.x), floor_div16(bounds.min.y),
                                                         floor_div16(bounds.min.z)) * 16;
    glm::ivec3 shift = bounds.empty() ? glm::ivec3(0) : bounds.min - cube_origin;
    int reach = std::max({shift.x + extent.x, shift.y + extent.y, shift.z + extent.z, 1});
    int depth = std::max(VX_SV_MIN_DEPTH, int(std::bit_width(unsigned(reach - 1))));
    if (depth > VX_SV_MAX_DEPTH)
        fail("svdag: a world ", extent.x, " x ", extent.y, " x ", extent.z, " voxels needs a cube of 2^", depth,
             " voxels a side; the limit is 2^", VX_SV_MAX_DEPTH, " (the traversal's stack depth)");
    if (model.voxel_count() >= (std::uint64_t(1) << 32))
        fail("svdag: ", model.voxel_count(), " solid voxels, above the limit of 2^32 (32-bit voxel counts)");
    dag_frame frame{bounds.empty() ? glm::ivec3(0) : bounds.min, extent, shift, depth};

    // 1. Leaves and payload, chunk by chunk in Morton order.
    std::vector<std::pair<std::uint64_t, const voxel_model::chunk*>> chunks;
    chunks.reserve(model.chunk_count());
    model.for_each_chunk([&](glm::ivec3 origin, const voxel_model::chunk& c) {
        glm::uvec3 cc = glm::uvec3((origin - cube_origin) / 16);
        chunks.emplace_back(morton3(cc.x, cc.y, cc.z), &c);
    });
    std::sort(chunks.begin(), chunks.end(), [](auto& a, auto& b) { return a.first < b.first; });
    unsigned threads = resolve_build_threads(options.threads, chunks.size() / 64 + 1);
    std::vector<leaf_scan> parts(threads);
    run_build_threads(threads, [&](unsigned t) {
        std::size_t begin = chunks.size() * t / threads, end = chunks.size() * (t + 1) / threads;
        scan_chunks(std::span(chunks).subspan(begin, end - begin), parts[t]);
    });
    leaf_scan leaves;
    for (auto& p : parts) {
        leaves.keys.insert(leaves.keys.end(), p.keys.begin(), p.keys.end());
        leaves.masks.insert(leaves.masks.end(), p.masks.begin(), p.masks.end());
        leaves.payload.insert(leaves.payload.end(), p.payload.begin(), p.payload.end());
        p = {};
    }
    return assemble(std::move(leaves), frame, options, &model.palette());
}

}  // namespace svdag_build
}  // namespace voxray

