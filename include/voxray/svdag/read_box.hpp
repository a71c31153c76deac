// The sparse voxel DAG as a chunk source for the mesher (meshing/chunk_source.hpp): the
// payload of every voxel of a box, by a depth-first descent that enters only the subtrees
// meeting the box and counts the voxels of the others (a node's word 1, a leaf's popcount),
// so that each voxel keeps its depth-first index, which addresses its attribute
// (svdag/layout.h). Exact attributes only: a colour-block DAG (svdag_colours) holds
// colours, not the materials a mesh is made of.
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <span>

#include "voxray/core/box.hpp"
#include "voxray/core/error.hpp"
#include "voxray/svdag/layout.h"
#include "voxray/svdag/svdag.hpp"

namespace voxray {
namespace svdag_detail {

class box_reader {
public:
    box_reader(std::span<const std::uint32_t> words, const box3i& box, std::uint8_t* out)
        : w_(words.data()), out_(out), extent_(box.extent()) {
        glm::ivec3 origin, shift;
        for (int a = 0; a < 3; ++a) {
            origin[a] = std::int32_t(w_[VX_SV_HEADER_ORIGIN + a]);
            shift[a] = std::int32_t(w_[VX_SV_HEADER_SHIFT + a]);
        }
        query_ = {box.min - origin + shift, box.max - origin + shift};  // DAG coordinates
        depth_ = int(w_[VX_SV_HEADER_DEPTH]);
        attributes_ = w_ + w_[VX_SV_HEADER_ATTRIBUTES];
    }

    void read() {
        std::fill(out_, out_ + std::size_t(extent_.x) * extent_.y * extent_.z, std::uint8_t(0));
        if (!query_.empty()) descend(w_[VX_SV_HEADER_ROOT], 0, glm::ivec3(0), 0);
    }

private:
    std::uint64_t leaf_mask(std::uint32_t node) const {
        return std::uint64_t(w_[node]) | (std::uint64_t(w_[node + 1]) << 32);
    }

    // Whether the cube [corner, corner + edge) meets the box read.
    bool meets_query(glm::ivec3 corner, int edge) const {
        glm::ivec3 far = corner + edge;
        return corner.x < query_.max.x && corner.y < query_.max.y && corner.z < query_.max.z && query_.min.x < far.x &&
               query_.min.y < far.y && query_.min.z < far.z;
    }

    // Node `node` at `level` covers [at, at + 2^(D - level)); `base` is the depth-first
    // index of its first voxel.
    void descend(std::uint32_t node, int level, glm::ivec3 at, std::uint64_t base) {
        if (level == depth_ - VX_SV_LEAF_EDGE_BITS) {
            std::uint64_t mask = leaf_mask(node);
            for (std::uint64_t bits = mask; bits; bits &= bits - 1) {
                int i = std::countr_zero(bits);
                glm::ivec3 p = at + glm::ivec3(i & 3, (i >> 2) & 3, i >> 4);
                if (!query_.contains(p)) continue;
                std::uint64_t index = base + std::uint64_t(std::popcount(mask & ((std::uint64_t(1) << i) - 1)));
                glm::ivec3 q = p - query_.min;
                out_[(std::size_t(q.z) * extent_.y + std::size_t(q.y)) * extent_.x + std::size_t(q.x)] =
                    std::uint8_t(attributes_[VX_SV_ATTRIBUTE_WORD(index)] >> VX_SV_ATTRIBUTE_SHIFT(index));
            }
            return;
        }
        std::uint32_t mask = w_[node] & VX_SV_NODE_MASK_BITS;
        int half = 1 << (depth_ - 1 - level);
        const std::uint32_t children = std::uint32_t(std::popcount(mask));
        std::uint32_t slot = 0;
        for (int o = 0; o < 8; ++o) {
            if (!(mask >> o & 1u)) continue;
            std::uint64_t below = slot > 0 ? w_[node + VX_SV_NODE_BELOW(children, slot)] : 0u;
            std::uint32_t child = w_[node + VX_SV_NODE_CHILDREN + slot++];
            glm::ivec3 corner = at + glm::ivec3(o & 1, (o >> 1) & 1, (o >> 2) & 1) * half;
            if (meets_query(corner, half)) descend(child, level + 1, corner, base + below);
        }
    }

    const std::uint32_t* w_;
    std::uint8_t* out_;
    glm::ivec3 extent_;
    box3i query_;
    int depth_ = 0;
    const std::uint32_t* attributes_ = nullptr;
};

}  // namespace svdag_detail

inline void read_box(const svdag& dag, const box3i& box, std::uint8_t* out) {
    std::span<const std::uint32_t> w = dag.blob();
    if (w[VX_SV_HEADER_ATTRIBUTE_KIND] != VX_SV_ATTRIBUTES_EXACT)
        fail("svdag read_box: this DAG holds colour blocks (svdag_colours), not the materials a mesh is made of; "
             "mesh an svdag with exact attributes");
    svdag_detail::box_reader(w, box, out).read();
}

}  // namespace voxray
