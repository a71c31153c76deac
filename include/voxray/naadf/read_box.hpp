// NAADF as a chunk source for the mesher (meshing/chunk_source.hpp): the materials of a box
// of voxels, each 16^3 chunk decoded once from its cells, blocks and groups
// (naadf::read_box), so what is meshed is what is traced, edits included.
#pragma once
#include <cstdint>

#include "voxray/core/box.hpp"
#include "voxray/naadf/naadf.hpp"

namespace voxray {

inline void read_box(const naadf& structure, const box3i& box, std::uint8_t* out) { structure.read_box(box, out); }

}  // namespace voxray
