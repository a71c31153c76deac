// Addressing inside one brick (brickmap/layout.h): an occupancy bit per voxel,
// then one payload value per voxel, packed low bits first. Voxel index
// i = lx | ly << b | lz << 2b (b = log2 edge), so an x row is a run of consecutive
// indices that never straddles an occupancy word (edges 4, 8, 16 divide 32).
//
//   brick words:  [ occupancy: edge^3 / 32 words ][ payload: edge^3 * bits / 32 words ]
//   payload word: voxels j0 .. j0 + k - 1 (k = 32 / bits), voxel j0 in the lowest bits
//
// Invariant kept by every writer: occupancy bit set <=> payload value != 0. An empty
// brick is therefore all-zero words, which is what the free ring hands out.
//
// All accesses go through std::atomic_ref with relaxed order: callers hold the brick's
// lock (brickmap.hpp) for writes, so no read-modify-write atomics are needed, yet a
// concurrent get() reads well-defined values.
#pragma once
#include <array>
#include <atomic>
#include <bit>
#include <cstdint>
#include <type_traits>

#include "voxray/brickmap/layout.h"
#include "voxray/edit/edit_op.hpp"

namespace voxray {

template <class Payload, int Edge>
struct brick_codec {
    static_assert(Edge == 4 || Edge == 8 || Edge == 16, "brick edge must be 4, 8 or 16");
    static_assert(std::is_same_v<Payload, std::uint8_t> || std::is_same_v<Payload, std::uint16_t> ||
                      std::is_same_v<Payload, std::uint32_t>,
                  "brick payload must be uint8_t, uint16_t or uint32_t");

    static constexpr int edge = Edge;
    static constexpr int bits = std::countr_zero(unsigned(Edge));  // log2 edge
    static constexpr std::uint32_t voxels = std::uint32_t(Edge) * Edge * Edge;
    static constexpr std::uint32_t payload_bits = sizeof(Payload) * 8;
    static constexpr std::uint32_t per_word = 32 / payload_bits;  // k: payload values per word
    static constexpr std::uint32_t occupancy_words = voxels / 32;
    static constexpr std::uint32_t payload_words = voxels / per_word;
    static constexpr std::uint32_t words = occupancy_words + payload_words;
    static constexpr std::uint32_t value_mask = payload_bits == 32 ? 0xFFFFFFFFu : (1u << payload_bits) - 1;
    static constexpr std::uint32_t group_mask = per_word == 32 ? 0xFFFFFFFFu : (1u << per_word) - 1;

    static constexpr std::uint32_t index(std::uint32_t lx, std::uint32_t ly, std::uint32_t lz) {
        return VX_BM_VOXEL_INDEX(lx, ly, lz, std::uint32_t(bits));
    }

    static std::uint32_t load(const std::uint32_t* w) {
        return std::atomic_ref<std::uint32_t>(*const_cast<std::uint32_t*>(w)).load(std::memory_order_relaxed);
    }
    static void store(std::uint32_t* w, std::uint32_t v) {
        std::atomic_ref<std::uint32_t>(*w).store(v, std::memory_order_relaxed);
    }

    static Payload get(const std::uint32_t* brick, std::uint32_t i) {
        std::uint32_t w = load(brick + occupancy_words + i / per_word);
        return Payload((w >> ((i % per_word) * payload_bits)) & value_mask);
    }
    // Voxels i0 .. i0 + n - 1 (a run along x) into out: one load per payload word.
    static void get_run(const std::uint32_t* brick, std::uint32_t i0, std::uint32_t n, Payload* out) {
        for (std::uint32_t i = i0, end = i0 + n; i < end;) {
            std::uint32_t w = load(brick + occupancy_words + i / per_word);
            for (std::uint32_t k = i % per_word; k < per_word && i < end; ++k, ++i)
                *out++ = Payload((w >> (k * payload_bits)) & value_mask);
        }
    }

    // The value replicated into every slot of a payload word.
    static constexpr std::uint32_t replicate(Payload v) {
        std::uint32_t r = 0;
        for (std::uint32_t s = 0; s < per_word; ++s) r |= std::uint32_t(v) << (s * payload_bits);
        return r;
    }
    // Expands k selection bits (one per voxel of a payload word) into a payload-word mask.
    static constexpr std::uint32_t expand(std::uint32_t sel) {
        if constexpr (per_word == 1) return sel ? 0xFFFFFFFFu : 0u;
        else return expand_table[sel];
    }

    struct result {
        std::int32_t delta = 0;  // change of the solid-voxel count
        bool changed = false;    // any bit of the brick changed
    };

    // Applies `op` with value v to voxels [i0, i0 + n) (one occupancy word at most:
    // callers pass one x run, or whole brick-wide slabs through write_range).
    static result write_run(std::uint32_t* brick, std::uint32_t i0, std::uint32_t n, edit_op op, Payload v) {
        result r;
        std::uint32_t wi = i0 >> 5, b0 = i0 & 31;
        std::uint32_t m = n >= 32 ? 0xFFFFFFFFu : ((1u << n) - 1) << b0;
        std::uint32_t old = load(brick + wi);
        std::uint32_t sel;  // voxels whose payload is written
        std::uint32_t rep = replicate(v);
        switch (op) {
            case edit_op::fill: {
                std::uint32_t fresh = m & ~old;
                r.delta = std::popcount(fresh);
                if (fresh) store(brick + wi, old | m);
                sel = m;
                break;
            }
            case edit_op::erase: {
                std::uint32_t gone = m & old;
                r.delta = -std::popcount(gone);
                if (gone) { store(brick + wi, old & ~m); r.changed = true; }
                sel = gone;
                rep = 0;
                break;
            }
            default:  // paint
                sel = m & old;
                break;
        }
        if (!sel) return r;
        // Payload words covering this occupancy word: 32 / k of them.
        std::uint32_t* pay = brick + occupancy_words + wi * (32 / per_word);
        std::uint32_t g0 = std::countr_zero(sel) / per_word, g1 = (31 - std::countl_zero(sel)) / per_word;
        for (std::uint32_t g = g0; g <= g1; ++g) {
            std::uint32_t s = (sel >> (g * per_word)) & group_mask;
            if (!s) continue;
            std::uint32_t em = expand(s);
            std::uint32_t p = load(pay + g);
            std::uint32_t q = (p & ~em) | (rep & em);
            if (q != p) { store(pay + g, q); r.changed = true; }
        }
        if (r.delta) r.changed = true;
        return r;
    }

    // Sets one voxel to v (0 erases).
    static result write_voxel(std::uint32_t* brick, std::uint32_t i, Payload v) {
        return write_run(brick, i, 1, v ? edit_op::fill : edit_op::erase, v);
    }

    // Every voxel solid with value v (v != 0): the expansion of a solid top cell.
    static void fill_solid(std::uint32_t* brick, Payload v) {
        for (std::uint32_t w = 0; w < occupancy_words; ++w) store(brick + w, 0xFFFFFFFFu);
        std::uint32_t rep = replicate(v);
        for (std::uint32_t w = 0; w < payload_words; ++w) store(brick + occupancy_words + w, rep);
    }
    static void clear(std::uint32_t* brick) {
        for (std::uint32_t w = 0; w < words; ++w) store(brick + w, 0u);
    }
    // True when all voxels hold the same value; that value goes to `v`.
    static bool uniform(const std::uint32_t* brick, Payload& v) {
        v = get(brick, 0);
        std::uint32_t rep = replicate(v);
        for (std::uint32_t w = 0; w < payload_words; ++w)
            if (load(brick + occupancy_words + w) != rep) return false;
        return true;
    }
    static std::uint32_t count(const std::uint32_t* brick) {
        std::uint32_t n = 0;
        for (std::uint32_t w = 0; w < occupancy_words; ++w) n += std::popcount(load(brick + w));
        return n;
    }
    // Occupancy and payload agree (used when loading untrusted files); returns the
    // first payload word that disagrees, or `words` when all agree.
    static std::uint32_t first_inconsistent_word(const std::uint32_t* brick) {
        for (std::uint32_t g = 0; g < payload_words; ++g) {
            std::uint32_t p = brick[occupancy_words + g];
            std::uint32_t occ = (brick[(g * per_word) >> 5] >> ((g * per_word) & 31)) & group_mask;
            std::uint32_t nonzero = 0;
            for (std::uint32_t s = 0; s < per_word; ++s)
                if ((p >> (s * payload_bits)) & value_mask) nonzero |= 1u << s;
            if (nonzero != occ) return occupancy_words + g;
        }
        return words;
    }

private:
    static constexpr auto make_expand_table() {
        std::array<std::uint32_t, (per_word == 1 ? 2 : (1u << per_word))> t{};
        for (std::uint32_t s = 0; s < t.size(); ++s)
            for (std::uint32_t j = 0; j < per_word; ++j)
                if ((s >> j) & 1u) t[s] |= value_mask << (j * payload_bits);
        return t;
    }
    static constexpr auto expand_table = make_expand_table();
};

}  // namespace voxray
