// One call from a mesh file to a voxel model: picks the reader by extension
// (.obj, .ply; any letter case), voxelizes the surface and marks the model Y-up,
// the convention of both formats' usual sources.
#pragma once
#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <string>

#include "voxray/core/error.hpp"
#include "voxray/io/mesh.hpp"
#include "voxray/io/obj_reader.hpp"
#include "voxray/io/ply_reader.hpp"
#include "voxray/io/voxelizer.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::io {

struct mesh_load_options {
    unsigned threads = 0;  // voxelizer threads; 0: all hardware threads
    std::uint64_t max_cell_tests = voxelize_options{}.max_cell_tests;  // the voxelizer's work limit
};

inline bool is_mesh_path(const std::filesystem::path& path) {
    auto ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".obj" || ext == ".ply";
}

inline triangle_mesh load_mesh(const std::filesystem::path& path) {
    auto ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".obj") return read_obj(path);
    if (ext == ".ply") return read_ply(path);
    fail("mesh file ", path.string(), ": unknown extension '", ext, "' (supported: .obj, .ply)");
}

// `resolution`: voxels along the longest axis of the mesh bounds, 1..4096.
inline voxel_model load_mesh_model(const std::filesystem::path& path, int resolution,
                                   const mesh_load_options& opt = {}) {
    if (resolution < 1 || resolution > max_voxelize_resolution)  // before reading a large file
        fail("voxelization resolution ", resolution, " is outside the supported range 1..", max_voxelize_resolution);
    auto mesh = load_mesh(path);
    try {
        auto model = voxelize(mesh, {resolution, opt.threads, opt.max_cell_tests});
        model.up_axis = 1;
        return model;
    } catch (const error& e) {
        fail(path.string(), ": ", e.what());  // the voxelizer's message, with the file
    }
}

}  // namespace voxray::io
