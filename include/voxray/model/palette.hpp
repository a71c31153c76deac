// A palette of 256 entries, as in MagicaVoxel: index 0 means "empty", 1..255 are
// colours with a material. Voxels store only the index.
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <string>

namespace voxray {

enum class material_kind : std::uint8_t { diffuse, metal, glass, emit, blend, media, cloud };

struct material {
    material_kind kind = material_kind::diffuse;
    float roughness = 0.5f;
    float metalness = 0.0f;
    float ior = 1.5f;
    float emission = 0.0f;  // radiance scale for emit materials
    float transparency = 0.0f;
    bool operator==(const material&) const = default;
};

// What is wrong with a material's numbers ("" when nothing): each field within the range
// a renderer can use (MagicaVoxel's sliders: roughness, metalness and transparency in
// [0, 1], IOR in [1, 5]; emission finite and >= 0). Readers of files call it, so a bad
// value is an error naming the field, never a silent NaN later in a shader.
inline std::string material_range_error(const material& m) {
    struct field { const char* name; float value, lo, hi; };
    const field fields[] = {{"roughness", m.roughness, 0.0f, 1.0f},   {"metalness", m.metalness, 0.0f, 1.0f},
                            {"ior", m.ior, 1.0f, 5.0f},                {"transparency", m.transparency, 0.0f, 1.0f},
                            {"emission", m.emission, 0.0f, 3.4e38f}};
    for (const field& f : fields)
        if (!(f.value >= f.lo && f.value <= f.hi)) {  // also catches NaN
            std::ostringstream out;
            out << f.name << " " << f.value << " is outside [" << f.lo << ", " << f.hi << "]";
            return out.str();
        }
    if (int(m.kind) > int(material_kind::cloud)) return "material kind " + std::to_string(int(m.kind)) + " is unknown";
    return "";
}

struct rgba {
    std::uint8_t r = 0, g = 0, b = 0, a = 255;
    bool operator==(const rgba&) const = default;
};

// A colour as one word, r | g<<8 | b<<16 | a<<24 (what a structure that stores colours
// rather than palette indices returns as a hit's material).
inline std::uint32_t pack_rgba(rgba c) {
    return std::uint32_t(c.r) | (std::uint32_t(c.g) << 8) | (std::uint32_t(c.b) << 16) | (std::uint32_t(c.a) << 24);
}

// The largest RGB channel difference, in [0, 1], between a packed colour and a colour.
inline double colour_difference(std::uint32_t packed, rgba c) {
    const int channel[3] = {c.r, c.g, c.b};
    double d = 0;
    for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(double(int((packed >> (8 * k)) & 255u) - channel[k])) / 255.0);
    return d;
}

struct palette_entry {
    rgba colour;
    material mat;
    bool operator==(const palette_entry&) const = default;
};

class palette {
public:
    static constexpr int size = 256;

    palette_entry& operator[](std::uint8_t index) { return entries_[index]; }
    const palette_entry& operator[](std::uint8_t index) const { return entries_[index]; }
    // Number of entries (1..255) that differ from black/default: used by `voxray info`.
    int used_entries() const {
        int n = 0;
        for (int i = 1; i < size; ++i)
            if (entries_[i].colour.r || entries_[i].colour.g || entries_[i].colour.b) ++n;
        return n;
    }

    bool operator==(const palette&) const = default;

private:
    std::array<palette_entry, size> entries_{};
};

}  // namespace voxray
