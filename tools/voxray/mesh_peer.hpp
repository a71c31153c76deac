// The peer of POP levels in mesh-bench: meshoptimizer reducing each chunk's LOD-0 mesh to
// the triangle count that each POP level draws, with meshopt_simplify (keeps topology and
// borders) and meshopt_simplifySloppy (does not). Per level: the time, the triangles
// reached, meshoptimizer's own error estimate (relative to the mesh's extent) and, with
// the Vulkan backend, the image error of each against the level-0 picture beside the POP
// level's own (mesh_raster.hpp's level_images; `up_axis` orients the view).
#pragma once
#include <vector>

#include <nlohmann/json.hpp>

#include "voxray/meshing/chunk_mesh.hpp"

namespace voxray::tool {

nlohmann::json meshoptimizer_levels(const std::vector<meshing::chunk_mesh>& meshes, int up_axis);

}  // namespace voxray::tool
