// The peer of POP levels in mesh-bench: meshoptimizer reducing each chunk's LOD-0 mesh to
// the triangle count that each POP level draws, with meshopt_simplify (keeps topology and
// borders) and meshopt_simplifySloppy (does not). Per level: the time, the triangles
// reached and meshoptimizer's own error estimate (relative to the mesh's extent).
#pragma once
#include <vector>

#include <nlohmann/json.hpp>

#include "voxray/meshing/chunk_mesh.hpp"

namespace voxray::tool {

nlohmann::json meshoptimizer_levels(const std::vector<meshing::chunk_mesh>& meshes);

}  // namespace voxray::tool
