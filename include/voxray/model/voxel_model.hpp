// The input side of every structure: a sparse set of voxels, each a palette index
// (1..255; 0 is empty), plus the palette. Storage is a hash map of 16^3 chunks, so a
// world of 65536 voxels per axis costs memory for its occupied chunks only.
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include <glm/common.hpp>  // box.hpp uses glm::min/max
#include <glm/vec3.hpp>

#include "voxray/core/box.hpp"
#include "voxray/core/error.hpp"
#include "voxray/model/palette.hpp"

namespace voxray {

class voxel_model {
public:
    static constexpr int chunk_bits = 4;
    static constexpr int chunk_edge = 1 << chunk_bits;  // 16
    static constexpr int chunk_voxels = chunk_edge * chunk_edge * chunk_edge;
    // Coordinates must lie in [-limit, limit): 2^20 keeps chunk keys in 3 x 17 bits
    // and leaves room for worlds well beyond 65536 voxels per axis.
    static constexpr int coordinate_limit = 1 << 20;

    struct chunk {
        std::array<std::uint8_t, chunk_voxels> voxels{};  // x fastest, then y, then z
        std::uint32_t count = 0;                         // non-empty voxels
    };

    // Which model axis points up: 2 (Z) for MagicaVoxel and the procedural scenes,
    // 1 (Y) for sources such as OBJ/PLY meshes. Cameras and viewers read it; the
    // voxels themselves are never rotated.
    int up_axis = 2;

    // Sets voxel p to palette index `value` (0 erases).
    void set(glm::ivec3 p, std::uint8_t value) {
        check_coordinate(p);
        auto key = chunk_key(p >> chunk_bits);
        auto it = chunks_.find(key);
        if (it == chunks_.end()) {
            if (value == 0) return;
            it = chunks_.emplace(key, std::make_unique<chunk>()).first;
        }
        chunk& c = *it->second;
        auto& v = c.voxels[local_index(p)];
        if (v == 0 && value != 0) { ++c.count; ++count_; }
        if (v != 0 && value == 0) { --c.count; --count_; }
        v = value;
        if (value != 0) bounds_.include(p);
        if (c.count == 0) chunks_.erase(it);
        bounds_dirty_ |= value == 0;
    }

    // Bulk path for generators and the voxelizer: puts a whole chunk at chunk
    // coordinate `cc` (its voxels start at cc * 16), replacing any chunk there.
    // The chunk's count is recomputed here, so callers fill only `voxels`; an
    // all-empty chunk just erases. Far cheaper than 4096 set() calls.
    void replace_chunk(glm::ivec3 cc, std::unique_ptr<chunk> c) {
        check_coordinate(cc * chunk_edge);
        auto key = chunk_key(cc);
        auto it = chunks_.find(key);
        if (it != chunks_.end()) {
            count_ -= it->second->count;
            chunks_.erase(it);
            bounds_dirty_ = true;  // the old chunk may have held the extreme voxels
        }
        if (!c) return;
        box3i local;
        std::uint32_t n = count_row_spans(*c, local);
        c->count = n;
        if (n == 0) return;
        count_ += n;
        if (!bounds_dirty_) {
            glm::ivec3 origin = cc * chunk_edge;
            bounds_.include(box3i{origin + local.min, origin + local.max});
        }
        chunks_.emplace(key, std::move(c));
    }

    // Pre-sizes the chunk table when the caller knows roughly how many chunks come.
    void reserve_chunks(std::size_t n) { chunks_.reserve(n); }

    std::uint8_t get(glm::ivec3 p) const {
        if (!in_range(p)) return 0;
        auto it = chunks_.find(chunk_key(p >> chunk_bits));
        return it == chunks_.end() ? 0 : it->second->voxels[local_index(p)];
    }

    // The 16^3 chunk holding voxel p, or null where that chunk is empty.
    const chunk* find_chunk(glm::ivec3 p) const {
        if (!in_range(p)) return nullptr;
        auto it = chunks_.find(chunk_key(p >> chunk_bits));
        return it == chunks_.end() ? nullptr : it->second.get();
    }

    std::uint64_t voxel_count() const { return count_; }
    std::size_t chunk_count() const { return chunks_.size(); }

    // Tight bounds of the solid voxels (recomputed lazily after erases).
    box3i bounds() const {
        if (bounds_dirty_) recompute_bounds();
        return bounds_;
    }

    voxray::palette& palette() { return palette_; }
    const voxray::palette& palette() const { return palette_; }

    // Calls f(chunk_origin, chunk) for every non-empty chunk, in unspecified order.
    template <class F>
    void for_each_chunk(F&& f) const {
        for (auto& [key, c] : chunks_) f(key_origin(key), *c);
    }

    // Calls f(position, value) for every solid voxel.
    template <class F>
    void for_each_voxel(F&& f) const {
        for_each_chunk([&](glm::ivec3 origin, const chunk& c) {
            for (int i = 0; i < chunk_voxels; ++i)
                if (c.voxels[i]) f(origin + local_position(i), c.voxels[i]);
        });
    }

    static int local_index(glm::ivec3 p) {
        auto m = chunk_edge - 1;
        return (p.x & m) | ((p.y & m) << chunk_bits) | ((p.z & m) << (2 * chunk_bits));
    }
    static glm::ivec3 local_position(int i) {
        auto m = chunk_edge - 1;
        return {i & m, (i >> chunk_bits) & m, i >> (2 * chunk_bits)};
    }
    static bool in_range(glm::ivec3 p) {
        return p.x >= -coordinate_limit && p.y >= -coordinate_limit && p.z >= -coordinate_limit &&
               p.x < coordinate_limit && p.y < coordinate_limit && p.z < coordinate_limit;
    }

private:
    static void check_coordinate(glm::ivec3 p) {
        if (!in_range(p))
            fail("voxel (", p.x, ", ", p.y, ", ", p.z, ") is outside the model's coordinate limit of +-",
                 coordinate_limit);
    }
    // Chunk coordinates lie in [-2^16, 2^16): 17 bits each after the bias.
    static std::uint64_t chunk_key(glm::ivec3 c) {
        constexpr std::int64_t bias = coordinate_limit >> chunk_bits;
        return std::uint64_t(c.x + bias) | (std::uint64_t(c.y + bias) << 21) | (std::uint64_t(c.z + bias) << 42);
    }
    static glm::ivec3 key_origin(std::uint64_t key) {
        constexpr std::int64_t bias = coordinate_limit >> chunk_bits;
        auto part = [&](int shift) { return int(std::int64_t((key >> shift) & 0x1FFFFF) - bias) << chunk_bits; };
        return {part(0), part(21), part(42)};
    }
    // Counts a chunk's solid voxels and their local bounds, one 16-voxel x row
    // (two 64-bit words) at a time: empty rows, the common case, cost two loads.
    static std::uint32_t count_row_spans(const chunk& c, box3i& local) {
        constexpr std::uint64_t low7 = 0x7F7F7F7F7F7F7F7Full;
        std::uint32_t n = 0;
        for (int row = 0; row < chunk_edge * chunk_edge; ++row) {
            std::uint64_t w[2];
            std::memcpy(w, c.voxels.data() + row * chunk_edge, sizeof w);
            if ((w[0] | w[1]) == 0) continue;
            int first = chunk_edge, last = -1;
            for (int h = 0; h < 2; ++h) {
                // High bit of each byte set iff that byte is non-zero.
                std::uint64_t solid = (((w[h] & low7) + low7) | w[h]) & ~low7;
                if (!solid) continue;
                n += std::uint32_t(std::popcount(solid));
                bool little = std::endian::native == std::endian::little;
                int lo = (little ? std::countr_zero(solid) : std::countl_zero(solid)) / 8;
                int hi = 7 - (little ? std::countl_zero(solid) : std::countr_zero(solid)) / 8;
                first = std::min(first, h * 8 + lo);
                last = std::max(last, h * 8 + hi);
            }
            glm::ivec3 p{0, row & (chunk_edge - 1), row >> chunk_bits};
            local.include(box3i{{first, p.y, p.z}, {last + 1, p.y + 1, p.z + 1}});
        }
        return n;
    }
    void recompute_bounds() const {
        bounds_ = {};
        for_each_chunk([&](glm::ivec3 origin, const chunk& c) {
            for (int i = 0; i < chunk_voxels; ++i)
                if (c.voxels[i]) bounds_.include(origin + local_position(i));
        });
        bounds_dirty_ = false;
    }

    std::unordered_map<std::uint64_t, std::unique_ptr<chunk>> chunks_;
    std::uint64_t count_ = 0;
    mutable box3i bounds_;
    mutable bool bounds_dirty_ = false;
    voxray::palette palette_;
};

}  // namespace voxray
