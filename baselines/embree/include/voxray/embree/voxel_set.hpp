// A compact, read-only set of voxels with their materials: sorted 63-bit packed keys and a
// parallel byte array, 9 bytes a voxel, binary search to find one.
//
// The box scene answers inside starts with one lookup of the start voxel here before
// tracing, so enclosed voxels need no BVH leaf (tens of bytes each) at all. A sorted array
// beats a hash set for this: no load factor, no pointers, and one O(log n) lookup per ray is
// small next to a BVH traversal.
#pragma once
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

#include <glm/vec3.hpp>

#include "voxray/core/box.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::embree {

class voxel_set {
public:
    // Packs a coordinate in the model's range [-2^20, 2^20) into 3 x 21 bits, z most
    // significant, so sorting groups voxels by z slab, then row.
    //   bit 63 | 62 ........ 42 | 41 ........ 21 | 20 ......... 0
    //     0    |   z + 2^20     |   y + 2^20     |   x + 2^20
    static std::uint64_t key(glm::ivec3 p) {
        constexpr std::int64_t bias = voxel_model::coordinate_limit;
        return std::uint64_t(p.x + bias) | (std::uint64_t(p.y + bias) << 21) | (std::uint64_t(p.z + bias) << 42);
    }

    void reserve(std::size_t n) {
        keys_.reserve(n);
        materials_.reserve(n);
    }
    // Adds a voxel; call finish() before find().
    void add(glm::ivec3 p, std::uint8_t material) {
        keys_.push_back(key(p));
        materials_.push_back(material);
        bounds_.include(p);
    }
    // Sorts the keys (materials follow). Duplicates are not expected: a model has one value
    // per position.
    void finish() {
        std::vector<std::uint32_t> order(keys_.size());
        std::iota(order.begin(), order.end(), 0u);
        std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return keys_[a] < keys_[b]; });
        std::vector<std::uint64_t> keys(keys_.size());
        std::vector<std::uint8_t> materials(keys_.size());
        for (std::size_t i = 0; i < order.size(); ++i) {
            keys[i] = keys_[order[i]];
            materials[i] = materials_[order[i]];
        }
        keys_.swap(keys);
        materials_.swap(materials);
    }

    // Material of voxel p, or 0 when p is not in the set.
    std::uint8_t find(glm::ivec3 p) const {
        if (!bounds_.contains(p)) return 0;  // also keeps key() inside its bit range
        auto k = key(p);
        auto it = std::lower_bound(keys_.begin(), keys_.end(), k);
        return (it != keys_.end() && *it == k) ? materials_[std::size_t(it - keys_.begin())] : 0;
    }

    std::size_t size() const { return keys_.size(); }
    bool empty() const { return keys_.empty(); }
    const box3i& bounds() const { return bounds_; }
    std::size_t bytes() const {
        return keys_.capacity() * sizeof(std::uint64_t) + materials_.capacity() * sizeof(std::uint8_t);
    }

private:
    std::vector<std::uint64_t> keys_;
    std::vector<std::uint8_t> materials_;
    box3i bounds_;
};

}  // namespace voxray::embree
