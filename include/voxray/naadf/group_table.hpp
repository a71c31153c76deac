// The deduplicated voxel groups of NAADF: every mixed block points to a group of 64
// voxels (32 words), and blocks with the same 64 voxels share one group. Groups are found
// by the paper's polynomial hash, H = c0 + sum c_i v_i with c_i = 31^(64-i) mod 2^32, in
// an open-addressing table with linear probing that grows at 75 % load. Probing runs until
// it finds the group or a free slot, so it never gives up and never hands out another
// group (the reference falls back to a garbage block when its probe limit runs out).
#pragma once
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/naadf/layout.h"

namespace voxray::naadf_detail {

using voxel_group = std::array<std::uint32_t, VX_NA_GROUP_WORDS>;

inline std::uint32_t group_hash(const voxel_group& g) {
    static const std::array<std::uint32_t, 65> c = [] {
        std::array<std::uint32_t, 65> powers{};
        powers[0] = 1;
        for (int i = 1; i <= 64; ++i) powers[i] = powers[i - 1] * 31u;  // mod 2^32
        return powers;
    }();
    std::uint32_t h = c[64];
    for (int i = 0; i < 64; ++i) {
        std::uint32_t v = (g[VX_NA_VOXEL_WORD(i)] >> VX_NA_VOXEL_SHIFT(i)) & 0xFFFFu;
        h += c[64 - i] * v;
    }
    return h;
}

class group_table {
public:
    group_table() { slots_.assign(1024, free_slot); }

    // The index of group g, added if it is new.
    std::uint32_t intern(const voxel_group& g) {
        std::uint32_t h = group_hash(g);
        std::size_t mask = slots_.size() - 1;
        for (std::size_t i = h & mask;; i = (i + 1) & mask) {
            std::uint32_t index = slots_[i];
            if (index == free_slot) {
                if (hashes_.size() > VX_NA_MAX_INDEX)
                    fail("naadf: more than ", VX_NA_MAX_INDEX, " distinct voxel groups (30-bit group index)");
                index = std::uint32_t(hashes_.size());
                words_.insert(words_.end(), g.begin(), g.end());
                hashes_.push_back(h);
                slots_[i] = index;
                if (4 * hashes_.size() > 3 * slots_.size()) grow();
                return index;
            }
            if (hashes_[index] == h && same(index, g)) return index;
        }
    }

    std::size_t size() const { return hashes_.size(); }
    std::span<const std::uint32_t> words() const { return words_; }

private:
    static constexpr std::uint32_t free_slot = 0xFFFFFFFFu;

    bool same(std::uint32_t index, const voxel_group& g) const {
        const std::uint32_t* w = words_.data() + std::size_t(index) * VX_NA_GROUP_WORDS;
        for (int i = 0; i < VX_NA_GROUP_WORDS; ++i)
            if (w[i] != g[i]) return false;
        return true;
    }

    void grow() {
        std::vector<std::uint32_t> slots(slots_.size() * 2, free_slot);
        std::size_t mask = slots.size() - 1;
        for (std::uint32_t index = 0; index < hashes_.size(); ++index) {
            std::size_t i = hashes_[index] & mask;
            while (slots[i] != free_slot) i = (i + 1) & mask;
            slots[i] = index;
        }
        slots_.swap(slots);
    }

    std::vector<std::uint32_t> slots_;   // group index, or free_slot
    std::vector<std::uint32_t> hashes_;  // per group, to re-slot on growth without rehashing
    std::vector<std::uint32_t> words_;   // the groups, 32 words each: the blob's voxel area
};

}  // namespace voxray::naadf_detail
