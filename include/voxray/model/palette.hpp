// A palette of 256 entries, as in MagicaVoxel: index 0 means "empty", 1..255 are
// colours with a material. Voxels store only the index.
#pragma once
#include <array>
#include <cstdint>

namespace voxray {

enum class material_kind : std::uint8_t { diffuse, metal, glass, emit, blend, media, cloud };

struct material {
    material_kind kind = material_kind::diffuse;
    float roughness = 0.5f;
    float metalness = 0.0f;
    float ior = 1.5f;
    float emission = 0.0f;  // radiance scale for emit materials
    float transparency = 0.0f;
};

struct rgba {
    std::uint8_t r = 0, g = 0, b = 0, a = 255;
};

struct palette_entry {
    rgba colour;
    material mat;
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

private:
    std::array<palette_entry, size> entries_{};
};

}  // namespace voxray
