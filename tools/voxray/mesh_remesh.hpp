// Remeshing after edits in mesh-bench: the brickmap and NAADF built from the scene, their
// chunks meshed, then rounds of one seeded random edit each, applied to the structure and
// followed by remeshing the chunks it can change (meshing/remesh.hpp). Per structure: µs a
// remeshed chunk (reading it through the structure's read_box and meshing it), chunks per
// edit, the edit's own time, and µs to read one chunk whole.
#pragma once
#include <nlohmann/json.hpp>

#include "voxray/model/voxel_model.hpp"

namespace voxray::tool {

nlohmann::json remesh_figures(const voxel_model& model, int rounds);

}  // namespace voxray::tool
