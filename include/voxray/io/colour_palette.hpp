// A palette of at most 255 entries for the many colours of a coloured mesh's voxels, by
// median cut: the colours (weighted by how many voxels have each) start as one box, and the
// box with the widest channel range is split at its weighted median along that channel
// until there are enough boxes; each box's entry is its weighted mean. Every colour maps to
// its own box's entry. Deterministic: colours are processed in value order.
#pragma once
#include <algorithm>
#include <cstdint>
#include <numeric>
#include <unordered_map>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/model/palette.hpp"

namespace voxray::io {

struct colour_count {
    std::uint32_t rgb = 0;  // r | g << 8 | b << 16
    std::uint64_t count = 0;
};

struct median_cut_palette {
    std::vector<rgba> entries;                             // at most the asked number
    std::unordered_map<std::uint32_t, std::uint8_t> entry;  // colour -> index into entries
};

inline int colour_channel(std::uint32_t rgb, int channel) { return int((rgb >> (8 * channel)) & 255u); }

inline median_cut_palette median_cut(std::vector<colour_count> colours, int most) {
    if (most < 1 || most > 256) fail("median cut: ", most, " palette entries asked for (1..256)");
    std::sort(colours.begin(), colours.end(),
              [](const colour_count& a, const colour_count& b) { return a.rgb < b.rgb; });
    struct box {
        std::size_t begin, end;  // range of `colours`
        int widest = 0, range = 0;
    };
    auto measure = [&](box& b) {
        b.range = -1;
        for (int ch = 0; ch < 3; ++ch) {
            int lo = 255, hi = 0;
            for (std::size_t i = b.begin; i < b.end; ++i) {
                lo = std::min(lo, colour_channel(colours[i].rgb, ch));
                hi = std::max(hi, colour_channel(colours[i].rgb, ch));
            }
            if (hi - lo > b.range) b.range = hi - lo, b.widest = ch;
        }
    };
    std::vector<box> boxes;
    if (!colours.empty()) {
        boxes.push_back({0, colours.size()});
        measure(boxes[0]);
    }
    while (int(boxes.size()) < most) {
        // The widest box with two colours or more (the first of equals).
        std::size_t pick = boxes.size();
        for (std::size_t i = 0; i < boxes.size(); ++i)
            if (boxes[i].end - boxes[i].begin > 1 && (pick == boxes.size() || boxes[i].range > boxes[pick].range))
                pick = i;
        if (pick == boxes.size()) break;
        box b = boxes[pick];
        int ch = b.widest;
        std::sort(colours.begin() + std::ptrdiff_t(b.begin), colours.begin() + std::ptrdiff_t(b.end),
                  [ch](const colour_count& x, const colour_count& y) {
                      int cx = colour_channel(x.rgb, ch), cy = colour_channel(y.rgb, ch);
                      return cx != cy ? cx < cy : x.rgb < y.rgb;
                  });
        std::uint64_t total = 0, seen = 0;
        for (std::size_t i = b.begin; i < b.end; ++i) total += colours[i].count;
        std::size_t split = b.begin + 1;  // both halves keep at least one colour
        for (std::size_t i = b.begin; i + 1 < b.end; ++i) {
            seen += colours[i].count;
            split = i + 1;
            if (2 * seen >= total) break;
        }
        box low{b.begin, split}, high{split, b.end};
        measure(low), measure(high);
        boxes[pick] = low;
        boxes.push_back(high);
    }
    median_cut_palette out;
    for (const box& b : boxes) {
        double sum[3] = {0, 0, 0}, weight = 0;
        for (std::size_t i = b.begin; i < b.end; ++i) {
            double w = double(std::max<std::uint64_t>(colours[i].count, 1));
            for (int ch = 0; ch < 3; ++ch) sum[ch] += w * colour_channel(colours[i].rgb, ch);
            weight += w;
        }
        rgba c;
        c.r = std::uint8_t(sum[0] / weight + 0.5), c.g = std::uint8_t(sum[1] / weight + 0.5);
        c.b = std::uint8_t(sum[2] / weight + 0.5);
        for (std::size_t i = b.begin; i < b.end; ++i) out.entry[colours[i].rgb] = std::uint8_t(out.entries.size());
        out.entries.push_back(c);
    }
    return out;
}

}  // namespace voxray::io
