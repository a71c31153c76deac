// The bounding volume hierarchy over instance boxes that the entity pass walks
// (entities/layout.h: nodes of 8 words, leaves pointing into a list of instance slots).
// Built by median splits on the longest axis of the box centres, so its depth is about
// log2(instances / leaf size) and stays within VX_SC_MAX_DEPTH for every slot count a
// scene allows. When instances only move, refit() widens or shrinks the boxes above the
// moved ones and names the nodes it changed (their words are all a device must be sent).
#pragma once
#include <algorithm>
#include <functional>
#include <bit>
#include <cstdint>
#include <numeric>
#include <span>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/entities/layout.h"
#include "voxray/entities/pose.hpp"

namespace voxray {

class instance_bvh {
public:
    static constexpr std::uint32_t leaf_size = 4;

    // Builds the tree over `slots` (instance slot numbers) whose boxes are boxes[slot], with
    // up to `most_per_leaf` instances a leaf (everything in the root: only its box is read).
    void build(std::vector<std::uint32_t> slots, const std::vector<world_box>& boxes,
               std::uint32_t most_per_leaf = leaf_size) {
        most_per_leaf_ = most_per_leaf;
        nodes_.clear();
        parent_.clear();
        items_ = std::move(slots);
        leaf_of_.assign(boxes.size(), none);
        if (items_.empty()) return;
        nodes_.reserve(2 * items_.size() / most_per_leaf_ * VX_SC_NODE_WORDS + VX_SC_NODE_WORDS);
        add_node(none);
        std::uint32_t depth = split(0, 0, std::uint32_t(items_.size()), boxes, 1);
        if (depth > VX_SC_MAX_DEPTH)
            fail("entity BVH: ", depth, " levels for ", items_.size(), " instances, above the kernels' limit of ",
                 VX_SC_MAX_DEPTH);
    }

    // New boxes for the instances in `moved`: each leaf above one and every node above
    // such a leaf gets the union of its children again. Returns the nodes whose box
    // changed, in increasing order. Children are numbered after their parents (split
    // adds them so), so a pass over the marked nodes from the highest number down sees
    // every child before its parent; with many marks it is one sweep over all nodes.
    std::vector<std::uint32_t> refit(std::span<const std::uint32_t> moved, const std::vector<world_box>& boxes) {
        dirty_.assign(node_count(), 0u);
        std::vector<std::uint32_t> marked;
        for (std::uint32_t slot : moved) {
            std::uint32_t n = slot < leaf_of_.size() ? leaf_of_[slot] : none;
            for (; n != none && !dirty_[n]; n = parent_[n]) {
                dirty_[n] = 1u;
                marked.push_back(n);
            }
        }
        std::vector<std::uint32_t> changed;
        auto refit_node = [&](std::uint32_t n) {
            world_box b = node_is_leaf(n) ? leaf_box(n, boxes) : union_of(child_box(n, 0), child_box(n, 1));
            if (set_box(n, b)) changed.push_back(n);
        };
        if (marked.size() * 16 > node_count()) {
            for (std::uint32_t n = node_count(); n-- > 0;)
                if (dirty_[n]) refit_node(n);
        } else {
            std::sort(marked.begin(), marked.end(), std::greater<>());
            for (std::uint32_t n : marked) refit_node(n);
        }
        std::reverse(changed.begin(), changed.end());
        return changed;
    }

    const std::vector<std::uint32_t>& node_words() const { return nodes_; }
    const std::vector<std::uint32_t>& items() const { return items_; }
    std::uint32_t node_count() const { return std::uint32_t(nodes_.size() / VX_SC_NODE_WORDS); }

private:
    static constexpr std::uint32_t none = 0xFFFFFFFFu;

    std::uint32_t add_node(std::uint32_t parent) {
        nodes_.resize(nodes_.size() + VX_SC_NODE_WORDS, 0u);
        parent_.push_back(parent);
        return node_count() - 1;
    }
    bool node_is_leaf(std::uint32_t n) const { return nodes_[n * VX_SC_NODE_WORDS + VX_SC_NODE_COUNT] != 0; }
    world_box child_box(std::uint32_t n, std::uint32_t which) const {
        return box_of(nodes_[n * VX_SC_NODE_WORDS + VX_SC_NODE_FIRST] + which);
    }
    world_box box_of(std::uint32_t n) const {
        world_box b;
        for (int a = 0; a < 3; ++a) {
            b.min[a] = std::bit_cast<float>(nodes_[n * VX_SC_NODE_WORDS + VX_SC_NODE_MIN + a]);
            b.max[a] = std::bit_cast<float>(nodes_[n * VX_SC_NODE_WORDS + VX_SC_NODE_MAX + a]);
        }
        return b;
    }
    // Writes the box; whether it differs from the one there.
    bool set_box(std::uint32_t n, const world_box& b) {
        bool differs = false;
        for (int a = 0; a < 3; ++a) {
            for (auto [field, v] : {std::pair{VX_SC_NODE_MIN + a, b.min[a]}, std::pair{VX_SC_NODE_MAX + a, b.max[a]}}) {
                std::uint32_t& w = nodes_[n * VX_SC_NODE_WORDS + field];
                differs = differs || w != std::bit_cast<std::uint32_t>(v);
                w = std::bit_cast<std::uint32_t>(v);
            }
        }
        return differs;
    }
    static world_box union_of(const world_box& a, const world_box& b) {
        return {glm::min(a.min, b.min), glm::max(a.max, b.max)};
    }
    world_box leaf_box(std::uint32_t n, const std::vector<world_box>& boxes) const {
        std::uint32_t first = nodes_[n * VX_SC_NODE_WORDS + VX_SC_NODE_FIRST];
        std::uint32_t count = nodes_[n * VX_SC_NODE_WORDS + VX_SC_NODE_COUNT];
        world_box b = boxes[items_[first]];
        for (std::uint32_t k = 1; k < count; ++k) b = union_of(b, boxes[items_[first + k]]);
        return b;
    }

    // Node n over items_[begin, end) at depth `depth`; returns the subtree's deepest level.
    std::uint32_t split(std::uint32_t n, std::uint32_t begin, std::uint32_t end, const std::vector<world_box>& boxes,
                        std::uint32_t depth) {
        world_box all = boxes[items_[begin]];
        glm::vec3 lo = (all.min + all.max) * 0.5f, hi = lo;
        for (std::uint32_t k = begin + 1; k < end; ++k) {
            all = union_of(all, boxes[items_[k]]);
            glm::vec3 c = (boxes[items_[k]].min + boxes[items_[k]].max) * 0.5f;
            lo = glm::min(lo, c);
            hi = glm::max(hi, c);
        }
        set_box(n, all);
        if (end - begin <= most_per_leaf_) {
            nodes_[n * VX_SC_NODE_WORDS + VX_SC_NODE_FIRST] = begin;
            nodes_[n * VX_SC_NODE_WORDS + VX_SC_NODE_COUNT] = end - begin;
            for (std::uint32_t k = begin; k < end; ++k) leaf_of_[items_[k]] = n;
            return depth;
        }
        glm::vec3 spread = hi - lo;
        int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : spread.y >= spread.z ? 1 : 2;
        std::uint32_t mid = begin + (end - begin) / 2;
        std::nth_element(items_.begin() + begin, items_.begin() + mid, items_.begin() + end,
                         [&](std::uint32_t a, std::uint32_t b) {
                             float ca = boxes[a].min[axis] + boxes[a].max[axis];
                             float cb = boxes[b].min[axis] + boxes[b].max[axis];
                             return ca < cb || (ca == cb && a < b);
                         });
        std::uint32_t left = add_node(n);
        std::uint32_t right = add_node(n);
        nodes_[n * VX_SC_NODE_WORDS + VX_SC_NODE_FIRST] = left;
        nodes_[n * VX_SC_NODE_WORDS + VX_SC_NODE_COUNT] = 0;
        (void)right;  // the second child follows the first (entities/layout.h)
        return std::max(split(left, begin, mid, boxes, depth + 1), split(right, mid, end, boxes, depth + 1));
    }

    std::vector<std::uint32_t> nodes_;     // VX_SC_NODE_WORDS a node
    std::vector<std::uint32_t> parent_;    // per node; none for the root
    std::vector<std::uint32_t> items_;     // instance slots, grouped by leaf
    std::vector<std::uint32_t> leaf_of_;   // per slot: its leaf, or none
    std::vector<std::uint8_t> dirty_;      // refit's marks, per node (kept to spare allocations)
    std::uint32_t most_per_leaf_ = leaf_size;
};

}  // namespace voxray
