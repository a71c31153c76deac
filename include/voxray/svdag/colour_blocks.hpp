// Aokana's colour blocks: the colours of the solid voxels in depth-first order, cut into
// runs whose colours all lie within `max_error` (per channel, colours in [0, 1]) of the
// run's average; a run is stored as its start index and its average colour (RGBA8), and a
// binary search over the starts finds a voxel's run (svdag/kernel.h, vx_sv_attribute).
// Lossy, so for looks only: game attributes use the exact encoding.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "voxray/model/palette.hpp"

namespace voxray::svdag_build {

// What a block's colour may be off by: the block error, plus the rounding of its
// average to 8 bits.
inline double colour_tolerance(float max_error) { return double(max_error) + 0.5 / 255.0 + 1e-9; }

struct colour_blocks {
    std::vector<std::uint32_t> starts;   // first depth-first index of each block, ascending
    std::vector<std::uint32_t> colours;  // RGBA8 (pack_rgba) average of each block
    double max_error = 0, mean_error = 0;  // per voxel, the largest channel difference in [0, 1]
};

// A block grows while every colour in it stays within max_error of the running average
// (tracked through the per-channel min and max, so each voxel costs O(1)). `colours` are
// RGBA8 (pack_rgba) in depth-first order; only RGB is compared and averaged.
inline colour_blocks encode_colour_blocks(std::span<const std::uint32_t> colours, float max_error) {
    colour_blocks out;
    auto channels = [](std::uint32_t c) {
        return std::array<float, 3>{float(c & 255u) / 255.0f, float((c >> 8) & 255u) / 255.0f,
                                    float((c >> 16) & 255u) / 255.0f};
    };
    std::array<double, 3> sum{}, lo{}, hi{};
    std::size_t length = 0;
    auto close_block = [&] {
        if (length == 0) return;
        rgba avg;
        avg.r = std::uint8_t(std::lround(sum[0] / double(length) * 255.0));
        avg.g = std::uint8_t(std::lround(sum[1] / double(length) * 255.0));
        avg.b = std::uint8_t(std::lround(sum[2] / double(length) * 255.0));
        out.colours.push_back(pack_rgba(avg));
    };
    for (std::size_t i = 0; i < colours.size(); ++i) {
        auto c = channels(colours[i]);
        bool fits = length > 0;
        for (int k = 0; k < 3 && fits; ++k) {
            double avg = (sum[k] + c[k]) / double(length + 1);
            fits = std::max<double>(hi[k], c[k]) - avg <= max_error && avg - std::min<double>(lo[k], c[k]) <= max_error;
        }
        if (!fits) {
            close_block();
            out.starts.push_back(std::uint32_t(i));
            sum = {}, length = 0;
            for (int k = 0; k < 3; ++k) lo[k] = hi[k] = c[k];
        }
        for (int k = 0; k < 3; ++k) sum[k] += c[k], lo[k] = std::min<double>(lo[k], c[k]), hi[k] = std::max<double>(hi[k], c[k]);
        ++length;
    }
    close_block();

    // The error each voxel ends up with, after the average is rounded to 8 bits.
    double total = 0;
    std::size_t block = 0;
    for (std::size_t i = 0; i < colours.size(); ++i) {
        while (block + 1 < out.starts.size() && out.starts[block + 1] <= i) ++block;
        std::uint32_t c = colours[i];
        double error = colour_difference(out.colours[block], rgba{std::uint8_t(c), std::uint8_t(c >> 8), std::uint8_t(c >> 16)});
        out.max_error = std::max(out.max_error, error);
        total += error;
    }
    out.mean_error = colours.empty() ? 0.0 : total / double(colours.size());
    return out;
}

// Palette indices: the blocks of their palette colours.
inline colour_blocks encode_colour_blocks(std::span<const std::uint8_t> payload, const palette& pal, float max_error) {
    std::vector<std::uint32_t> colours(payload.size());
    for (std::size_t i = 0; i < payload.size(); ++i) colours[i] = pack_rgba(pal[payload[i]].colour);
    return encode_colour_blocks(colours, max_error);
}

}  // namespace voxray::svdag_build
