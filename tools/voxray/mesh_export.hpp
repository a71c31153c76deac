// Chunk meshes out to files that other tools read: PLY (quads, vertex colours) and glTF 2.0
// (triangles, vertex colours; .glb binary or .gltf with the buffer embedded, through
// tinygltf). Both carry the quads drawn at one level of detail, corners rounded to it.
#pragma once
#include <string>
#include <vector>

#include "voxray/meshing/chunk_mesh.hpp"
#include "voxray/model/palette.hpp"

namespace voxray::tool {

void write_mesh_ply(const std::string& path, const std::vector<meshing::chunk_mesh>& meshes, const palette& colours, int level);
void write_mesh_gltf(const std::string& path, const std::vector<meshing::chunk_mesh>& meshes, const palette& colours, int level);

}  // namespace voxray::tool
