// The deduplicated voxel groups of NAADF: every mixed block points to a group of 64
// voxels (32 words), and blocks with the same 64 voxels share one group. Groups are found
// by the paper's polynomial hash, H = c0 + sum c_i v_i with c_i = 31^(64-i) mod 2^32, in
// an open-addressing table with linear probing that grows at 75 % load. Probing runs until
// it finds the group or a free slot, so it never gives up and never hands out another
// group (the reference falls back to a garbage block when its probe limit runs out).
//
// Edits keep the table: each group counts the blocks that use it, and a group no block
// uses leaves the table (backward-shift deletion, so no tombstones slow probing later)
// and its index is handed out again, so a long editing session reuses the blob's group
// slots instead of growing them.
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <memory>
#include <cstdint>
#include <functional>
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

    struct interned {
        std::uint32_t index;
        bool added;  // a new group: its words must be written
    };

    // The index of group g (hash h = group_hash(g)), added if it is new; one more user.
    interned intern(const voxel_group& g, std::uint32_t h) {
        std::size_t mask = slots_.size() - 1;
        for (std::size_t i = home(h, slots_.size());; i = (i + 1) & mask) {
            std::uint32_t index = slots_[i];
            if (index == free_slot) {
                index = take_index();
                segments_[index / segment_groups][index % segment_groups] = g;
                hashes_[index] = h;
                users_[index] = 1;
                slots_[i] = index;
                if (4 * (size() - free_.size()) > 3 * slots_.size()) grow();
                return {index, true};
            }
            if (hashes_[index] == h && same(index, g)) {
                ++users_[index];
                return {index, false};
            }
        }
    }
    std::uint32_t intern(const voxel_group& g) { return intern(g, group_hash(g)).index; }

    // Whether group g (hash h) is in the table, without adding it: safe from many
    // threads while nobody interns or releases.
    bool contains(const voxel_group& g, std::uint32_t h) const {
        std::size_t mask = slots_.size() - 1;
        for (std::size_t i = home(h, slots_.size());; i = (i + 1) & mask) {
            std::uint32_t index = slots_[i];
            if (index == free_slot) return false;
            if (hashes_[index] == h && same(index, g)) return true;
        }
    }

    // One user fewer; the last one's release frees the group's index for reuse.
    void release(std::uint32_t index) {
        if (--users_[index] != 0) return;
        erase_slot(index);
        free_index(index);
    }

    // Appends group g as index size() with `users` users (loading a file, in index order:
    // the blob decides where groups are). users = 0: a free index.
    void adopt(const voxel_group& g, std::uint32_t users) {
        std::uint32_t index = take_index(true);
        segments_[index / segment_groups][index % segment_groups] = g;
        hashes_[index] = group_hash(g);
        users_[index] = users;
        if (users == 0) return free_index(index);
        std::size_t mask = slots_.size() - 1;
        std::size_t i = home(hashes_[index], slots_.size());
        for (; slots_[i] != free_slot; i = (i + 1) & mask)
            if (hashes_[slots_[i]] == hashes_[index] && same(slots_[i], g)) return;  // a duplicate: the first serves
        slots_[i] = index;
        if (4 * (size() - free_.size()) > 3 * slots_.size()) grow();
    }

    // Groups in use (size() counts free indices too: it is how many the blob holds).
    std::size_t live() const { return size() - free_.size(); }
    std::uint32_t users(std::uint32_t index) const { return users_[index]; }

    std::size_t size() const { return hashes_.size(); }
    const voxel_group& group(std::uint32_t index) const { return segments_[index / segment_groups][index % segment_groups]; }

    // Copies every group, in index order, to `out` (size() * 32 words).
    void copy_to(std::uint32_t* out) const {
        for (std::size_t n = 0; n < size(); n += segment_groups) {
            std::size_t count = std::min<std::size_t>(segment_groups, size() - n);
            std::memcpy(out + n * VX_NA_GROUP_WORDS, segments_[n / segment_groups].get(), count * sizeof(voxel_group));
        }
    }

private:
    static constexpr std::uint32_t free_slot = 0xFFFFFFFFu;
    // Groups live in fixed segments, so a new one never moves the others (no copying and
    // no second round of page faults as the table grows).
    static constexpr std::size_t segment_groups = 4096;

    // The slot a hash starts probing at: the polynomial hash's low bits follow the voxel
    // types' low bits only, so they are spread (Fibonacci hashing: the top bits of h times
    // 2^32 / golden ratio) before they pick one of `slots` (a power of two).
    static std::size_t home(std::uint32_t h, std::size_t slots) {
        std::uint64_t spread = std::uint64_t(h * 0x9E3779B9u) << 32;
        return std::size_t(spread >> (64 - std::countr_zero(slots)));
    }

    bool same(std::uint32_t index, const voxel_group& g) const {
        return group(index) == g;
    }

    // A fresh index: the lowest freed one first (a min-heap), so the blob's groups stay
    // packed at the front, else (or with `append`) a new one.
    std::uint32_t take_index(bool append = false) {
        if (!free_.empty() && !append) {
            std::pop_heap(free_.begin(), free_.end(), std::greater<>());
            std::uint32_t index = free_.back();
            free_.pop_back();
            return index;
        }
        if (hashes_.size() > VX_NA_MAX_INDEX)
            fail("naadf: more than ", VX_NA_MAX_INDEX, " distinct voxel groups (30-bit group index)");
        std::uint32_t index = std::uint32_t(hashes_.size());
        if (index % segment_groups == 0) segments_.push_back(std::make_unique_for_overwrite<voxel_group[]>(segment_groups));
        hashes_.push_back(0);
        users_.push_back(0);
        return index;
    }

    void free_index(std::uint32_t index) {
        free_.push_back(index);
        std::push_heap(free_.begin(), free_.end(), std::greater<>());
    }

    // Removes `index` from the slots; later members of its probe run move back into the
    // hole when their home allows it (so every run stays unbroken, no tombstones).
    void erase_slot(std::uint32_t index) {
        std::size_t mask = slots_.size() - 1;
        std::size_t hole = home(hashes_[index], slots_.size());
        while (slots_[hole] != index) {
            if (slots_[hole] == free_slot) return;  // an adopted duplicate never had a slot
            hole = (hole + 1) & mask;
        }
        for (std::size_t next = (hole + 1) & mask; slots_[next] != free_slot; next = (next + 1) & mask) {
            std::size_t want = home(hashes_[slots_[next]], slots_.size());
            // `next` may fill the hole if its home is not in (hole, next], cyclically.
            bool stays = hole <= next ? (want > hole && want <= next) : (want > hole || want <= next);
            if (stays) continue;
            slots_[hole] = slots_[next];
            hole = next;
        }
        slots_[hole] = free_slot;
    }

    void grow() {
        std::vector<std::uint32_t> slots(slots_.size() * 2, free_slot);
        std::size_t mask = slots.size() - 1;
        for (std::uint32_t index = 0; index < hashes_.size(); ++index) {
            if (users_[index] == 0) continue;
            std::size_t i = home(hashes_[index], slots.size());
            while (slots[i] != free_slot) i = (i + 1) & mask;
            slots[i] = index;
        }
        slots_.swap(slots);
    }

    std::vector<std::uint32_t> slots_;   // group index, or free_slot
    std::vector<std::uint32_t> hashes_;  // per group, to re-slot on growth without rehashing
    std::vector<std::uint32_t> users_;   // per group: blocks using it (0: free)
    std::vector<std::uint32_t> free_;    // indices of free groups (a min-heap)
    std::vector<std::unique_ptr<voxel_group[]>> segments_;
};

}  // namespace voxray::naadf_detail
