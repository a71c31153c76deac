// The chunk lists of a scene (entities/layout.h): the NAADF paper's way to find the
// instances a ray may meet. Space is cut into 16^3 chunks; each chunk's word names the list
// of instances whose boxes reach it, and chunks with the same instances share one list;
// each instance's world box is kept beside them. The kernel walks the chunks along the ray
// and tests an instance in the chunk where the ray enters its box (entities/pass.h,
// vx_entities_trace_chunks).
//
// The grid covers the instances' boxes (each grown by a voxel, so a point the kernel's
// rounding puts in a neighbouring chunk still finds its instance there). A move rewrites
// the instance's box and, only where the chunks it reaches change, the lists of the chunks
// it left or entered: the changed lists are appended (lists in use stay where they are),
// so a frame's words follow what moved. A full build (instances added or removed, one
// leaving the grid, or the appended lists outgrowing those packed at the last build) places
// the grid anew and packs the lists.
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

#include "voxray/core/blob.hpp"
#include "voxray/core/error.hpp"
#include "voxray/core/word_range.hpp"
#include "voxray/entities/layout.h"
#include "voxray/entities/pose.hpp"

namespace voxray {

class chunk_lists {
public:
    // The most chunks a grid may have (64 MiB of chunk words): instances spread wider are an
    // error that says so, and the BVH serves such scenes.
    static constexpr std::uint64_t max_chunks = std::uint64_t(1) << 24;

    // Builds the section's words over the instances `live` (slot numbers, increasing) whose
    // boxes are boxes[slot], with room for the boxes of `slots` slots.
    void build(std::span<const std::uint32_t> live, const std::vector<world_box>& boxes, std::uint32_t slots) {
        place_grid(live, boxes);
        std::uint32_t chunks = std::uint32_t(size_[0] * size_[1] * size_[2]);
        chunk_words_ = VX_SC_CHUNK_BOXES + slots * VX_SC_CHUNK_BOX_WORDS;
        words_.assign(chunk_words_ + chunks, 0u);
        shared_.clear();
        for (int a = 0; a < 3; ++a) {
            words_[VX_SC_CHUNK_MIN + a] = std::uint32_t(min_[a]);
            words_[VX_SC_CHUNK_SIZE + a] = std::uint32_t(size_[a]);
        }
        words_[VX_SC_CHUNK_WORDS] = chunk_words_;  // free slots' boxes stay zeros: no list names them
        members_.resize(chunks);
        for (auto& m : members_) m.clear();
        is_dirty_.assign(chunks, 0);
        reach_.assign(slots, {});
        for (std::uint32_t slot : live) {  // in increasing order, so every list is sorted
            write_box(slot, boxes[slot]);
            reach_[slot] = chunks_reached(boxes[slot]);
            for_each_chunk(reach_[slot], [&](std::uint32_t c) { members_[c].push_back(slot); });
        }
        for (std::uint32_t c = 0; c < chunks; ++c)
            if (!members_[c].empty()) words_[chunk_words_ + c] = list_offset(members_[c]);
        packed_words_ = std::uint32_t(words_.size());
    }

    // Instances `moved` (increasing) have new boxes, boxes[slot]: their box words, and the
    // lists of the chunks they left or entered. changed() names the words it wrote. False
    // where the lists must be built again instead (more than a quarter of the instances
    // moved: a build is then faster, measured; a box left the grid; or the lists appended
    // since the last build outweigh those it packed): nothing else is valid then.
    bool move(std::span<const std::uint32_t> moved, const std::vector<world_box>& boxes, std::size_t live) {
        if (moved.size() * 4 > live) return false;
        changed_.clear();
        dirty_.clear();
        for (std::uint32_t slot : moved) {
            auto r = chunks_reached(boxes[slot]);
            for (int a = 0; a < 3; ++a)
                if (r[a] < 0 || r[3 + a] >= size_[a]) return false;
            write_box(slot, boxes[slot]);
            append_joined(changed_, VX_SC_CHUNK_BOXES + slot * VX_SC_CHUNK_BOX_WORDS, VX_SC_CHUNK_BOX_WORDS);
            if (r == reach_[slot]) continue;
            for_each_chunk(reach_[slot], [&](std::uint32_t c) {
                members_[c].erase(std::lower_bound(members_[c].begin(), members_[c].end(), slot));
                mark_dirty(c);
            });
            for_each_chunk(r, [&](std::uint32_t c) {
                members_[c].insert(std::lower_bound(members_[c].begin(), members_[c].end(), slot), slot);
                mark_dirty(c);
            });
            reach_[slot] = r;
        }
        std::sort(dirty_.begin(), dirty_.end());  // chunk words in increasing order
        for (std::uint32_t c : dirty_) is_dirty_[c] = 0;
        std::uint32_t appended_from = std::uint32_t(words_.size());
        for (std::uint32_t c : dirty_) {
            std::uint32_t list = members_[c].empty() ? 0u : list_offset(members_[c]);  // (may grow words_)
            if (words_[chunk_words_ + c] == list) continue;
            words_[chunk_words_ + c] = list;
            append_joined(changed_, chunk_words_ + c, 1);
        }
        std::uint32_t appended = std::uint32_t(words_.size()) - appended_from;
        if (appended > 0) append_joined(changed_, appended_from, appended);
        return words_.size() - packed_words_ <= packed_words_;
    }

    const std::vector<std::uint32_t>& words() const { return words_; }
    // The words the last move() wrote, increasing, from the section's start.
    const std::vector<word_range>& changed() const { return changed_; }

private:
    static std::int64_t floor_chunk(double v) { return std::int64_t(std::floor(v / VX_SC_CHUNK_EDGE)); }
    using reach = std::array<std::int32_t, 6>;  // chunks reached: lo x, y, z, hi x, y, z (inclusive)

    // The grid: the instances' chunks, kept from the last build where it still covers them
    // and has at most twice the chunks they need.
    void place_grid(std::span<const std::uint32_t> live, const std::vector<world_box>& boxes) {
        std::array<std::int64_t, 3> lo{0, 0, 0}, hi{0, 0, 0};  // chunk range, inclusive
        for (std::size_t i = 0; i < live.size(); ++i) {
            const world_box& b = boxes[live[i]];
            for (int a = 0; a < 3; ++a) {
                if (!(std::abs(double(b.min[a])) < limit && std::abs(double(b.max[a])) < limit))
                    fail("scene chunk lists: instance ", live[i], " reaches ", a == 0 ? "x" : a == 1 ? "y" : "z", " = ",
                         std::abs(double(b.min[a])) >= limit ? b.min[a] : b.max[a], ", beyond the lists' range of +-",
                         limit, " voxels");
                std::int64_t l = floor_chunk(double(b.min[a]) - 1.0), h = floor_chunk(double(b.max[a]) + 1.0);
                lo[a] = i == 0 ? l : std::min(lo[a], l);
                hi[a] = i == 0 ? h : std::max(hi[a], h);
            }
        }
        std::uint64_t needed = 1, kept = 1;
        bool covers = true;
        for (int a = 0; a < 3; ++a) {
            needed *= std::uint64_t(hi[a] - lo[a] + 1);
            std::int64_t from = min_[a] / VX_SC_CHUNK_EDGE;
            covers = covers && from <= lo[a] && hi[a] < from + size_[a];
            kept *= std::uint64_t(size_[a]);
        }
        if (covers && kept <= 2 * needed) return;
        if (needed > max_chunks)
            fail("scene chunk lists: the instances span ", hi[0] - lo[0] + 1, " x ", hi[1] - lo[1] + 1, " x ",
                 hi[2] - lo[2] + 1, " chunks of ", VX_SC_CHUNK_EDGE, "^3 voxels, above the limit of ", max_chunks,
                 " chunks; find candidates by the BVH (entity_candidates::bvh) instead");
        for (int a = 0; a < 3; ++a) {
            min_[a] = lo[a] * VX_SC_CHUNK_EDGE;
            size_[a] = hi[a] - lo[a] + 1;
        }
    }

    // The grid's chunks that box b grown by a voxel reaches (may lie outside the grid).
    reach chunks_reached(const world_box& b) const {
        reach r;
        for (int a = 0; a < 3; ++a) {
            std::int64_t from = min_[a] / VX_SC_CHUNK_EDGE;
            r[a] = std::int32_t(std::clamp<std::int64_t>(floor_chunk(double(b.min[a]) - 1.0) - from, -1, size_[a]));
            r[3 + a] = std::int32_t(std::clamp<std::int64_t>(floor_chunk(double(b.max[a]) + 1.0) - from, -1, size_[a]));
        }
        return r;
    }

    template <class F>
    void for_each_chunk(const reach& r, F&& f) const {
        for (std::int64_t z = r[2]; z <= r[5]; ++z)
            for (std::int64_t y = r[1]; y <= r[4]; ++y)
                for (std::int64_t x = r[0]; x <= r[3]; ++x) f(std::uint32_t(x + size_[0] * (y + size_[1] * z)));
    }

    void mark_dirty(std::uint32_t c) {
        if (is_dirty_[c]) return;
        is_dirty_[c] = 1;
        dirty_.push_back(c);
    }

    void write_box(std::uint32_t slot, const world_box& b) {
        std::uint32_t* box = words_.data() + VX_SC_CHUNK_BOXES + slot * VX_SC_CHUNK_BOX_WORDS;
        for (int a = 0; a < 3; ++a) {
            box[VX_SC_NODE_MIN + a] = std::bit_cast<std::uint32_t>(b.min[a]);
            box[VX_SC_NODE_MAX + a] = std::bit_cast<std::uint32_t>(b.max[a]);
        }
    }

    bool holds(std::uint32_t at, std::span<const std::uint32_t> list) const {
        return at + 1 + list.size() <= words_.size() && words_[at] == list.size() &&
               std::equal(list.begin(), list.end(), words_.begin() + at + 1);
    }

    // Where `list` lies in the words: an equal list already written, else appended.
    std::uint32_t list_offset(std::span<const std::uint32_t> list) {
        std::uint64_t h = 1469598103934665603ull;  // FNV-1a over the slots
        for (std::uint32_t s : list) h = (h ^ s) * 1099511628211ull;
        auto found = shared_.find(h);
        if (found != shared_.end() && holds(found->second, list)) return found->second;
        std::uint32_t at = std::uint32_t(words_.size());
        check_blob_size("scene chunk lists", std::uint64_t(at) + 1 + list.size());
        words_.push_back(std::uint32_t(list.size()));
        words_.insert(words_.end(), list.begin(), list.end());
        shared_.insert_or_assign(h, at);  // a collision: the newer list is found
        return at;
    }

    // Box coordinates the lists accept: chunk numbers and corners stay far inside 32 bits.
    static constexpr double limit = double(1 << 30);

    std::array<std::int64_t, 3> min_{0, 0, 0}, size_{0, 0, 0};
    std::uint32_t chunk_words_ = 0, packed_words_ = 0;  // offset of the chunk words; words at the last build
    std::vector<std::uint32_t> words_;
    std::vector<std::vector<std::uint32_t>> members_;  // per chunk: the slots whose boxes reach it, increasing
    std::vector<reach> reach_;                          // per slot: the chunks its box reaches
    std::unordered_map<std::uint64_t, std::uint32_t> shared_;  // offsets of lists written, by a hash of their slots
    std::vector<std::uint32_t> dirty_;                  // move(): chunks whose lists changed, once each
    std::vector<std::uint8_t> is_dirty_;                // per chunk: listed in dirty_
    std::vector<word_range> changed_;
};

}  // namespace voxray
