// The cells of one model chunk (NAADF paper, section 3.2): its 64 blocks, each empty
// (with its AADF inside the chunk), uniform, or mixed with a group of 64 voxels; a chunk
// whose blocks are all uniform with one type collapses. Groups hold types only here; the
// empty voxels' fields are written once per distinct group, after deduplication
// (add_group_fields), since they follow from the types.
#pragma once
#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <vector>

#include "voxray/model/build_threads.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/naadf/aadf.hpp"
#include "voxray/naadf/group_table.hpp"
#include "voxray/naadf/layout.h"

namespace voxray::naadf_detail {

// One model chunk as NAADF cells, before its groups are interned.
struct built_chunk {
    std::uint32_t cell = 0;                  // uniform, or mixed (index filled in later)
    std::array<std::uint32_t, 64> blocks{};  // mixed blocks hold their local group number
    std::vector<voxel_group> groups;
    std::uint64_t kept = 0;  // mixed blocks not rebuilt (an edit left them as they were)
};

// Model-chunk offset of voxel i (x | y << 2 | z << 4) of a block, from the block's base.
inline const std::array<std::uint16_t, 64>& block_offsets() {
    static const std::array<std::uint16_t, 64> offsets = [] {
        std::array<std::uint16_t, 64> o{};
        for (int i = 0; i < 64; ++i) o[i] = std::uint16_t(voxel_model::local_index({i & 3, (i >> 2) & 3, i >> 4}));
        return o;
    }();
    return offsets;
}

// The cells of model chunk c; with `fields`, the empty blocks' AADFs too. Mixed blocks
// outside `rebuild` get no group: they are marked in out.kept (an edit keeps their
// old cell).
inline void build_chunk(const voxel_model::chunk& c, bool fields, built_chunk& out, std::uint64_t rebuild = ~std::uint64_t(0)) {
    const auto& offsets = block_offsets();
    out.groups.clear();
    out.kept = 0;
    std::uint64_t solid_blocks = 0;
    bool uniform = true;
    for (int b = 0; b < 64; ++b) {
        const std::uint8_t* base = c.voxels.data() + voxel_model::local_index(glm::ivec3(b & 3, (b >> 2) & 3, b >> 4) * 4);
        // A block is 16 rows of 4 bytes: empty and uniform blocks are told apart from them.
        std::uint32_t any = 0, differs = 0, first = std::uint32_t(base[0]) * 0x01010101u;
        for (int row = 0; row < 16; ++row) {
            std::uint32_t r;
            std::memcpy(&r, base + (row & 3) * voxel_model::chunk_edge + (row >> 2) * voxel_model::chunk_edge * voxel_model::chunk_edge, 4);
            any |= r;
            differs |= r ^ first;
        }
        if (any == 0) {
            uniform = false;
            out.blocks[b] = 0;
            continue;
        }
        bool same = differs == 0;
        solid_blocks |= std::uint64_t(1) << b;
        std::uint32_t cell;
        if (same) {
            cell = VX_NA_UNIFORM_CELL(std::uint32_t(base[0]));
        } else if (!(rebuild >> b & 1u)) {
            cell = VX_NA_MIXED_CELL(0);
            out.kept |= std::uint64_t(1) << b;
        } else {
            voxel_group g{};
            for (int i = 0; i < 64; ++i)
                if (std::uint32_t t = base[offsets[i]]) g[VX_NA_VOXEL_WORD(i)] |= VX_NA_SOLID_VOXEL(t) << VX_NA_VOXEL_SHIFT(i);
            cell = VX_NA_MIXED_CELL(std::uint32_t(out.groups.size()));
            out.groups.push_back(g);
        }
        uniform = uniform && VX_NA_STATE(cell) == VX_NA_UNIFORM && (b == 0 || cell == out.blocks[0]);
        out.blocks[b] = cell;
    }
    if (uniform) {
        out.cell = out.blocks[0];
        return;
    }
    if (fields) {
        auto aadfs = grid4_aadfs(solid_blocks, VX_NA_BLOCK_AADF_BITS);
        for (int b = 0; b < 64; ++b)
            if (!((solid_blocks >> b) & 1u)) out.blocks[b] = aadfs[b];
    }
    out.cell = VX_NA_MIXED_CELL(0);
}

// The voxel fields of 4^3 solid masks, remembered: edits and builds meet the same masks
// over and over (a sphere's surface wherever it moves, flat ground, walls), and a lookup
// costs a fraction of growing 64 cuboids. One per worker thread (not thread-safe).
class field_cache {
public:
    const std::array<std::uint16_t, 64>& fields(std::uint64_t solid) {
        entry& e = entries_[(solid * 0x9E3779B97F4A7C15ull) >> (64 - bits)];
        if (e.solid != solid) {
            auto aadfs = grid4_aadfs(solid, VX_NA_VOXEL_AADF_BITS);
            for (int i = 0; i < 64; ++i) e.fields[i] = std::uint16_t(aadfs[i]);
            e.solid = solid;
        }
        return e.fields;
    }

private:
    static constexpr int bits = 14;
    struct entry {
        std::uint64_t solid = ~std::uint64_t(0);  // a group is never all solid: never looked up
        std::array<std::uint16_t, 64> fields{};
    };
    std::vector<entry> entries_ = std::vector<entry>(std::size_t(1) << bits);
};

// Adds the distance fields of a group's empty voxels to its types (32 words in place).
inline void add_fields(std::uint32_t* g, field_cache& cache) {
    std::uint64_t solid = 0;
    for (int i = 0; i < 64; ++i)
        solid |= std::uint64_t((g[VX_NA_VOXEL_WORD(i)] >> VX_NA_VOXEL_SHIFT(i)) & VX_NA_VOXEL_SOLID ? 1 : 0) << i;
    const auto& fields = cache.fields(solid);
    for (int i = 0; i < 64; ++i) g[VX_NA_VOXEL_WORD(i)] |= std::uint32_t(fields[i]) << VX_NA_VOXEL_SHIFT(i);
}

// Writes the distance fields of the empty voxels of `count` groups (type-only until now).
inline void add_group_fields(std::uint32_t* words, std::size_t count, unsigned requested_threads) {
    unsigned threads = resolve_build_threads(requested_threads, count / 256);
    run_build_threads(threads, [&](unsigned id) {
        field_cache cache;
        for (std::size_t n = id; n < count; n += threads) add_fields(words + n * VX_NA_GROUP_WORDS, cache);
    });
}

// The types of a chunk's voxels (the inverse of build_chunk): `cell` is the chunk's cell,
// `blocks` and `groups` the blob's areas (word pointers at array / group 0).
inline void decode_chunk(std::uint32_t cell, const std::uint32_t* blocks, const std::uint32_t* groups, voxel_model::chunk& out) {
    auto& v = out.voxels;
    if (VX_NA_STATE(cell) != VX_NA_MIXED) {
        std::uint8_t t = VX_NA_STATE(cell) == VX_NA_UNIFORM ? std::uint8_t(cell & VX_NA_TYPE_MASK) : 0;
        std::fill(v.begin(), v.end(), t);
        return;
    }
    const auto& offsets = block_offsets();
    const std::uint32_t* array = blocks + std::uint64_t(VX_NA_PAYLOAD(cell)) * VX_NA_BLOCK_ARRAY_WORDS;
    for (int b = 0; b < 64; ++b) {
        std::uint8_t* base = v.data() + voxel_model::local_index(glm::ivec3(b & 3, (b >> 2) & 3, b >> 4) * 4);
        std::uint32_t block = array[b];
        if (VX_NA_STATE(block) != VX_NA_MIXED) {
            std::uint32_t row4 = (VX_NA_STATE(block) == VX_NA_UNIFORM ? block & VX_NA_TYPE_MASK : 0u) * 0x01010101u;
            for (int row = 0; row < 16; ++row)
                std::memcpy(base + (row & 3) * voxel_model::chunk_edge + (row >> 2) * voxel_model::chunk_edge * voxel_model::chunk_edge, &row4, 4);
            continue;
        }
        const std::uint32_t* g = groups + std::uint64_t(VX_NA_PAYLOAD(block)) * VX_NA_GROUP_WORDS;
        for (int i = 0; i < 64; ++i) {
            std::uint32_t voxel = g[VX_NA_VOXEL_WORD(i)] >> VX_NA_VOXEL_SHIFT(i);
            base[offsets[i]] = voxel & VX_NA_VOXEL_SOLID ? std::uint8_t(voxel & VX_NA_TYPE_MASK) : 0;
        }
    }
}

}  // namespace voxray::naadf_detail
