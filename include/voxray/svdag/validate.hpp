// Structural validation of a sparse voxel DAG blob (svdag/layout.h) that came from
// outside (a chunk file, a network packet): after it passes, a kernel may walk every
// pointer without reading past the blob, looping or indexing past the attributes.
//
// What is checked, in order: the header (size, magic, version, depth, root, attribute
// kind), the node and attribute regions (inside the blob, attributes after the nodes),
// then the DAG from the root, level by level: each distinct node once (a node reached at
// two depths is an error), every node and child pointer inside the node region, children
// strictly after their parent (the builder's root-first, level-by-level order; it also
// rules out cycles), mask bits above 8 zero, no empty node but an empty root, every count
// below a child the sum of the voxels of the children before it and the header's voxel
// count the root's (computed bottom-up, level by level, without recursion): the kernel's
// depth-first index then stays below it. Last the attributes against that count. Time and
// memory are linear in the number of distinct nodes (one hash-map entry each).
#pragma once
#include <bit>
#include <cstdint>
#include <span>
#include <string>
#include <unordered_map>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/svdag/layout.h"

namespace voxray {
namespace svdag_detail {

// Validates `w`; a failure calls bad(word, message parts...), which must throw.
template <class Bad>
void validate_blob(std::span<const std::uint32_t> w, Bad&& bad) {
    const std::uint64_t size = w.size();
    if (size < VX_SV_HEADER_WORDS)
        bad(size, "blob of ", size, " words is shorter than the ", VX_SV_HEADER_WORDS, "-word header");
    auto expect = [&](std::uint64_t word, std::uint64_t want, const char* what) {
        if (w[word] != want) bad(word, what, " ", w[word], " (expected ", want, ")");
    };
    expect(VX_SV_HEADER_MAGIC, VX_SV_MAGIC, "blob magic");
    expect(VX_SV_HEADER_VERSION, VX_SV_VERSION, "blob layout version");
    const std::uint32_t depth = w[VX_SV_HEADER_DEPTH];
    if (depth < VX_SV_MIN_DEPTH || depth > VX_SV_MAX_DEPTH)
        bad(VX_SV_HEADER_DEPTH, "depth ", depth, " is outside [", VX_SV_MIN_DEPTH, ", ", VX_SV_MAX_DEPTH, "]");
    expect(VX_SV_HEADER_ROOT, VX_SV_HEADER_WORDS, "root pointer");

    // Regions. 64-bit sums: a hostile word must not wrap around into the blob.
    const std::uint64_t node_begin = VX_SV_HEADER_WORDS, node_end = node_begin + w[VX_SV_HEADER_NODE_WORDS];
    if (node_end > size)
        bad(VX_SV_HEADER_NODE_WORDS, "node region of ", w[VX_SV_HEADER_NODE_WORDS], " words ends at word ", node_end,
            ", past the blob's ", size, " words");
    const std::uint32_t kind = w[VX_SV_HEADER_ATTRIBUTE_KIND];
    if (kind != VX_SV_ATTRIBUTES_EXACT && kind != VX_SV_ATTRIBUTES_COLOUR_BLOCKS)
        bad(VX_SV_HEADER_ATTRIBUTE_KIND, "attribute kind ", kind, " is unknown (expected ", VX_SV_ATTRIBUTES_EXACT,
            " exact or ", VX_SV_ATTRIBUTES_COLOUR_BLOCKS, " colour blocks)");
    const std::uint64_t count = w[VX_SV_HEADER_ATTRIBUTE_COUNT];
    // A region of `words` words at the offset in header word `at`: after the nodes, inside the blob.
    auto region = [&](std::uint64_t at, std::uint64_t words, const char* what) {
        std::uint64_t begin = w[at];
        if (begin < node_end) bad(at, what, " at word ", begin, " overlaps the node region, which ends at word ", node_end);
        if (begin + words > size)
            bad(at, what, " of ", words, " words at word ", begin, " ends at word ", begin + words, ", past the blob's ",
                size, " words");
        return begin;
    };
    const bool exact = kind == VX_SV_ATTRIBUTES_EXACT;
    std::uint64_t starts = 0;
    if (exact) {
        region(VX_SV_HEADER_ATTRIBUTES, (count + 3) / 4, "exact attributes");
    } else {
        starts = region(VX_SV_HEADER_ATTRIBUTES, count, "colour block starts");
        std::uint64_t colours = region(VX_SV_HEADER_COLOURS, count, "colour block colours");
        if (colours < starts + count && starts < colours + count)
            bad(VX_SV_HEADER_COLOURS, "colour block colours at word ", colours, " overlap the ", count,
                " block starts at word ", starts);
        // The kernel's binary search starts from the largest power of two <= count.
        expect(VX_SV_HEADER_SEARCH_TOP, std::bit_floor(count), "colour block search top");
    }

    // The walk, level by level from the root. Each distinct node: its depth and count.
    struct node_info {
        std::uint32_t depth;
        std::uint64_t count;
    };
    std::unordered_map<std::uint32_t, node_info> seen;
    const std::uint32_t leaf_depth = depth - VX_SV_LEAF_EDGE_BITS;
    std::vector<std::vector<std::uint32_t>> levels(leaf_depth + 1);
    levels[0].push_back(VX_SV_HEADER_WORDS);
    seen[VX_SV_HEADER_WORDS] = {0, 0};
    for (std::uint32_t d = 0; d < leaf_depth; ++d) {
        for (std::uint32_t at : levels[d]) {
            // Its mask word first, so that reading the mask stays inside the region.
            if (std::uint64_t(at) + 1 > node_end)
                bad(at, "node ends at word ", std::uint64_t(at) + 1, ", past the node region's end at word ", node_end);
            std::uint32_t mask = w[at];
            if (mask & ~VX_SV_NODE_MASK_BITS) bad(at, "node mask ", mask, " has bits above bit 7 (limit ", VX_SV_NODE_MASK_BITS, ")");
            if (mask == 0 && d != 0) bad(at, "node at depth ", d, " has an empty child mask (only the root may be empty)");
            const std::uint64_t children = std::uint64_t(std::popcount(mask));
            std::uint64_t end = std::uint64_t(at) + VX_SV_NODE_WORDS(children);
            if (end > node_end)
                bad(at, "node of ", end - at, " words ends at word ", end, ", past the node region's end at word ", node_end);
            const std::uint64_t first_child = std::uint64_t(at) + VX_SV_NODE_CHILDREN;
            for (std::uint64_t slot = first_child; slot < first_child + children; ++slot) {
                std::uint32_t child = w[slot];
                if (child <= at || child >= node_end)
                    bad(slot, "child pointer ", child, " of the node at word ", at, " is outside (", at, ", ", node_end,
                        ") (children lie after their parent, inside the node region)");
                auto [it, fresh] = seen.try_emplace(child, node_info{d + 1, 0});
                if (fresh) levels[d + 1].push_back(child);
                else if (it->second.depth != d + 1)
                    bad(slot, "child pointer ", child, " reaches a node at depth ", d + 1, " that is also at depth ",
                        it->second.depth);
            }
        }
    }
    for (std::uint32_t at : levels[leaf_depth]) {
        if (std::uint64_t(at) + VX_SV_LEAF_WORDS > node_end)
            bad(at, "leaf ends at word ", std::uint64_t(at) + VX_SV_LEAF_WORDS, ", past the node region's end at word ", node_end);
        std::uint64_t n = std::uint64_t(std::popcount(w[at])) + std::popcount(w[at + 1]);
        if (n == 0) bad(at, "leaf has an empty mask (", w[at], ", ", w[at + 1], ")");
        seen[at].count = n;
    }
    // Counts bottom-up: every child of level d is on level d + 1, already summed.
    for (std::uint32_t d = leaf_depth; d-- > 0;) {
        for (std::uint32_t at : levels[d]) {
            std::uint64_t n = 0;
            const int children = std::popcount(w[at]);
            for (int k = 0; k < children; ++k) {
                const std::uint64_t below = std::uint64_t(at) + VX_SV_NODE_BELOW(children, k);
                if (k > 0 && w[below] != n)
                    bad(below, "count below child ", k, " is ", w[below], ", not its earlier siblings' sum ", n);
                n += seen[w[at + VX_SV_NODE_CHILDREN + k]].count;
            }
            seen[at].count = n;
        }
    }
    const std::uint64_t voxels = w[VX_SV_HEADER_VOXELS];
    if (voxels != seen[VX_SV_HEADER_WORDS].count)
        bad(VX_SV_HEADER_VOXELS, "voxel count ", voxels, " in the header is not the nodes' ",
            seen[VX_SV_HEADER_WORDS].count);

    // Attributes against the voxels.
    if (exact) {
        if (count != voxels) bad(VX_SV_HEADER_ATTRIBUTE_COUNT, "exact attribute count ", count, " is not the DAG's voxel count ", voxels);
        return;
    }
    // Every voxel needs a block: none only without voxels, and the first starts at 0.
    if (count == 0 && voxels != 0) bad(VX_SV_HEADER_ATTRIBUTE_COUNT, "no colour blocks for ", voxels, " voxels");
    for (std::uint64_t i = 0; i < count; ++i) {
        std::uint32_t s = w[starts + i];
        if (i == 0 && s != 0) bad(starts, "first colour block starts at ", s, " (expected 0)");
        if (i > 0 && s <= w[starts + i - 1])
            bad(starts + i, "colour block start ", s, " is not above the previous start ", w[starts + i - 1]);
        if (s >= voxels) bad(starts + i, "colour block start ", s, " is not below the voxel count ", voxels);
    }
}

}  // namespace svdag_detail

// Throws voxray::error "<what>: word <offset>: <problem>" on the first problem found.
inline void validate_svdag_blob(std::span<const std::uint32_t> words, const std::string& what) {
    svdag_detail::validate_blob(words, [&](std::uint64_t word, auto&&... parts) {
        fail(what, ": word ", word, ": ", parts...);
    });
}

}  // namespace voxray
