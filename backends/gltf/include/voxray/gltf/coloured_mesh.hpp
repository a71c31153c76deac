// One call from a mesh file to a coloured voxel model: glTF (.gltf, .glb; gltf_reader.hpp),
// OBJ with its MTL files and textures (io/obj_reader.hpp, texture_files.hpp) and PLY (no
// colour: its groups' palette), voxelized so that each voxel takes the colour of what it
// covers (io/voxelizer.hpp). The model is Y-up, the convention of all three formats.
#pragma once
#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>

#include "voxray/core/error.hpp"
#include "voxray/gltf/gltf_reader.hpp"
#include "voxray/gltf/texture_files.hpp"
#include "voxray/io/mesh_loader.hpp"
#include "voxray/io/obj_reader.hpp"
#include "voxray/io/ply_reader.hpp"
#include "voxray/io/voxelizer.hpp"

namespace voxray::gltf {

inline std::string lower_extension(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext;
}

inline bool is_coloured_mesh_path(const std::filesystem::path& path) {
    std::string ext = lower_extension(path);
    return ext == ".gltf" || ext == ".glb" || io::is_mesh_path(path);
}

inline io::triangle_mesh load_coloured_mesh(const std::filesystem::path& path) {
    std::string ext = lower_extension(path);
    if (ext == ".gltf" || ext == ".glb") return read_gltf(path);
    if (ext == ".obj") {
        io::triangle_mesh mesh = io::read_obj(path, {.materials = true});
        decode_textures(mesh.surface);
        mesh.validate();
        return mesh;
    }
    if (ext == ".ply") return io::read_ply(path);
    fail("mesh file ", path.string(), ": unknown extension '", ext, "' (supported: .gltf, .glb, .obj, .ply)");
}

// `resolution`: voxels along the longest axis of the mesh bounds, 1..4096.
inline voxel_model load_coloured_mesh_model(const std::filesystem::path& path, int resolution,
                                            const io::mesh_load_options& opt = {}) {
    if (resolution < 1 || resolution > io::max_voxelize_resolution)
        fail("voxelization resolution ", resolution, " is outside the supported range 1..",
             io::max_voxelize_resolution);
    io::triangle_mesh mesh = load_coloured_mesh(path);
    try {
        voxel_model model = io::voxelize(mesh, {resolution, opt.threads, opt.max_cell_tests});
        model.up_axis = 1;
        return model;
    } catch (const error& e) {
        fail(path.string(), ": ", e.what());
    }
}

}  // namespace voxray::gltf
