// Colours for mesh groups: each OBJ group (or PLY file) gets one palette entry,
// coloured by a hash of its name, so the same group keeps its colour across runs,
// resolutions and machines. Group g uses palette index 1 + g % 255: with more
// than 255 groups the indices wrap and later groups share earlier colours.
#pragma once
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "voxray/model/palette.hpp"

namespace voxray::io {

inline std::uint8_t group_palette_index(std::uint32_t group) { return std::uint8_t(1 + group % 255); }

// FNV-1a, then a final avalanche so similar names ("object3", "object4") differ.
inline std::uint32_t group_name_hash(std::string_view name) {
    std::uint32_t h = 2166136261u;
    for (unsigned char c : name) h = (h ^ c) * 16777619u;
    h ^= h >> 16;
    h *= 0x7feb352du;
    h ^= h >> 15;
    h *= 0x846ca68bu;
    return h ^ (h >> 16);
}

// Muted, light colours (HSV with moderate saturation and high value): shading
// stays readable in renders and neighbouring groups still differ in hue.
inline rgba group_colour(std::string_view name) {
    std::uint32_t h = group_name_hash(name);
    double hue = double(h % 360u);
    double sat = 0.35 + 0.25 * double((h >> 9) % 256u) / 255.0;
    double val = 0.72 + 0.22 * double((h >> 17) % 256u) / 255.0;
    double c = val * sat, x = c * (1.0 - std::fabs(std::fmod(hue / 60.0, 2.0) - 1.0)), m = val - c;
    double r = 0, g = 0, b = 0;
    switch (int(hue / 60.0)) {
        case 0: r = c, g = x; break;
        case 1: r = x, g = c; break;
        case 2: g = c, b = x; break;
        case 3: g = x, b = c; break;
        case 4: r = x, b = c; break;
        default: r = c, b = x; break;
    }
    auto byte = [&](double v) { return std::uint8_t(std::lround((v + m) * 255.0)); };
    return {byte(r), byte(g), byte(b), 255};
}

// Fills palette entries for the groups; with wrapping, the first group wins.
inline void assign_group_palette(palette& pal, const std::vector<std::string>& group_names) {
    for (std::size_t g = 0; g < group_names.size() && g < 255; ++g)
        pal[group_palette_index(std::uint32_t(g))].colour = group_colour(group_names[g]);
}

}  // namespace voxray::io
