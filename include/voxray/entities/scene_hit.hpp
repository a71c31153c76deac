// What a scene's hit says (entities/layout.h): the world's voxel, or an instance's voxel and
// face in its model's own coordinates, with the instance in the material word's upper bits.
#pragma once
#include <cstdint>
#include <optional>

#include "voxray/core/hit.hpp"
#include "voxray/entities/layout.h"

namespace voxray {

// The instance a hit is on; none for a world hit or a miss.
inline std::optional<std::uint32_t> hit_instance(const hit& h) {
    std::uint32_t above = h.material >> VX_SC_INSTANCE_SHIFT;
    if (!h.is_hit() || above == 0) return std::nullopt;
    return above - 1;
}

// The palette index of the hit voxel, in the world's or the instance's model's palette.
inline std::uint8_t hit_palette_index(const hit& h) { return std::uint8_t(h.material & 0xFFu); }

}  // namespace voxray
