// A test-only editable structure for the incremental-update tests: a dense grid's blob
// whose words the test changes directly, reporting the words it touched as dirty ranges
// (the interface tracer::update(Structure&) looks for). Edits stay inside the chunk
// records (occupancy bits and material bytes), where any 32-bit value is a valid grid,
// so every edited blob can still be traced; ranges may also cover words that did not
// change (header, chunk table), as a structure's coarse dirty tracking would.
#pragma once
#include <algorithm>
#include <cstdint>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "voxray/check/ray_sets.hpp"
#include "voxray/core/box.hpp"
#include "voxray/dense_grid/layout.h"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/core/word_range.hpp"

namespace voxray::test {

struct edited_grid {
    using kernel = kernels::dense_grid_kernel;
    static constexpr std::string_view name = "edited_grid";

    std::vector<std::uint32_t> words;
    std::vector<word_range> dirty;
    box3i bounds;

    explicit edited_grid(const dense_grid& grid)
        : words(grid.blob().begin(), grid.blob().end()), bounds(grid.bounds()) {}

    std::span<const std::uint32_t> blob() const { return words; }
    std::vector<word_range> take_dirty_ranges() { return std::exchange(dirty, {}); }

    std::uint32_t data_begin() const { return words[VX_DG_HEADER_DATA]; }
    std::uint32_t size() const { return std::uint32_t(words.size()); }
};

// The kinds of update the property test mixes; each appears in the first kinds_count steps.
enum class edit_kind { random, overlapping, adjacent, at_end, none, tiny_many, covers_header, huge, loose, count };
inline constexpr int kinds_count = int(edit_kind::count);

// Changes the words of [offset, offset + count) that lie in the chunk records: flips one
// bit (an occupancy or material change) or writes a random word.
inline void scramble(edited_grid& g, rng& r, std::uint32_t offset, std::uint32_t count) {
    for (std::uint32_t i = std::max(offset, g.data_begin()); i < offset + count && i < g.size(); ++i)
        g.words[i] = r.below(2) ? g.words[i] ^ (1u << r.below(32)) : std::uint32_t(r.next());
}

// A random range inside the chunk records, of 1..max_count words.
inline word_range random_data_range(const edited_grid& g, rng& r, std::uint32_t max_count) {
    std::uint32_t span = g.size() - g.data_begin();
    std::uint32_t count = 1 + std::uint32_t(r.below(int(std::min(max_count, span))));
    std::uint32_t offset = g.data_begin() + std::uint32_t(r.below(int(span - count + 1)));
    return {offset, count};
}

// Applies one edit of `kind` to g.words and returns dirty ranges covering every changed word.
inline std::vector<word_range> make_edit(edited_grid& g, rng& r, edit_kind kind) {
    std::vector<word_range> out;
    auto edit = [&](word_range w) {
        scramble(g, r, w.offset, w.count);
        out.push_back(w);
    };
    switch (kind) {
    case edit_kind::random:
        for (int n = 1 + r.below(20); n > 0; --n) edit(random_data_range(g, r, 300));
        break;
    case edit_kind::overlapping: {  // ranges inside, straddling and repeating one region
        word_range base = random_data_range(g, r, 600);
        edit(base);
        for (int n = 2 + r.below(10); n > 0; --n) {
            std::uint32_t a = base.offset + std::uint32_t(r.below(int(base.count)));
            std::uint32_t end = std::min(g.size(), a + 1 + std::uint32_t(r.below(int(base.count))));
            edit({a, end - a});
        }
        out.push_back(base);  // the same range twice
        break;
    }
    case edit_kind::adjacent: {  // back-to-back ranges, reported in shuffled order
        word_range at = random_data_range(g, r, 1);
        for (int n = 2 + r.below(12); n > 0 && at.offset < g.size(); --n) {
            std::uint32_t count = std::min<std::uint32_t>(1 + r.below(40), g.size() - at.offset);
            edit({at.offset, count});
            at.offset += count;
        }
        for (std::size_t i = out.size(); i > 1; --i) std::swap(out[i - 1], out[std::size_t(r.below(int(i)))]);
        break;
    }
    case edit_kind::at_end:  // the very last words, and the very last word alone
        edit({g.size() - 1, 1});
        edit({g.size() - 200 + std::uint32_t(r.below(150)), 0});
        out.back().count = g.size() - out.back().offset;
        scramble(g, r, out.back().offset, out.back().count);
        break;
    case edit_kind::none:  // no change: no ranges, or only empty ones (one at the end)
        if (r.below(2)) out = {{g.data_begin(), 0}, {g.size(), 0}, {0, 0}};
        break;
    case edit_kind::tiny_many:  // thousands of one- and two-word ranges
        for (int n = 3000 + r.below(2000); n > 0; --n) edit(random_data_range(g, r, 2));
        break;
    case edit_kind::covers_header:  // unchanged header and table words are dirty too
        out.push_back({0, g.data_begin()});
        edit(random_data_range(g, r, 64));
        break;
    case edit_kind::huge:  // most of the blob: the packet would not be smaller than it
        edit({g.data_begin(), g.size() - g.data_begin()});
        break;
    case edit_kind::loose:  // ranges wider than the changed words
        for (int n = 1 + r.below(6); n > 0; --n) {
            word_range w = random_data_range(g, r, 100);
            scramble(g, r, w.offset + w.count / 3, w.count / 3 + 1);
            out.push_back(w);
        }
        break;
    case edit_kind::count: break;
    }
    return out;
}

}  // namespace voxray::test
