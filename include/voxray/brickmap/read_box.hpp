// The brickmap as a chunk source for the mesher (meshing/chunk_source.hpp): the materials of
// a box of voxels, read from its top grid and bricks (brickmap::read_box), so what is
// meshed is what is traced, edits included. For 8-bit payloads: the mesher's materials.
#pragma once
#include <cstdint>

#include "voxray/brickmap/brickmap.hpp"
#include "voxray/core/box.hpp"

namespace voxray {

template <int BrickEdge>
inline void read_box(const brickmap<std::uint8_t, BrickEdge>& map, const box3i& box, std::uint8_t* out) {
    map.read_box(box, out);
}

}  // namespace voxray
