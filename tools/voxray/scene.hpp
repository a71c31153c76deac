// Loads a scene given on the command line: a .vox file, an .obj/.ply mesh (voxelized at
// --resolution), or builtin:NAME for the procedural scenes.
#pragma once
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>

#include "voxray/gltf/coloured_mesh.hpp"
#include "voxray/io/mesh_loader.hpp"
#include "voxray/io/vox_reader.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/scenes/builtin.hpp"

#include <CLI/CLI.hpp>

namespace voxray::tool {

// SCENE (one, or several for bench), --resolution and the input limits, as every
// command takes them. The limits bound what a small file may cost (issue 12, item 10).
struct scene_options {
    std::vector<std::string> scenes;
    int resolution = 512;
    std::uint64_t max_voxels = io::vox_options{}.max_placed_voxels;
    std::uint64_t max_model_mib = io::vox_options{}.max_model_bytes >> 20;
    std::uint64_t max_cell_tests = io::voxelize_options{}.max_cell_tests;

    // max_resolution: 4096 for a model voxelized whole; world-build voxelizes chunk by chunk.
    void add_to(CLI::App* app, bool many, int max_resolution = io::max_voxelize_resolution) {
        auto* opt = app->add_option("scene", scenes,
                                    many ? "one or more scenes (a file or builtin:NAME)"
                                         : "a .vox/.obj/.ply/.gltf/.glb file or builtin:NAME")
                        ->required();
        if (!many) opt->expected(1);
        app->add_option("--resolution", resolution, "voxels along a mesh's longest side")
            ->check(CLI::Range(1, max_resolution))
            ->capture_default_str();
        app->add_option("--max-voxels", max_voxels, "most voxels a .vox scene may place (instances counted)")
            ->check(CLI::Range(std::uint64_t(1), std::uint64_t(1) << 40))
            ->capture_default_str();
        app->add_option("--max-model-mib", max_model_mib, "most memory (MiB) a .vox scene's voxels may need")
            ->check(CLI::Range(std::uint64_t(1), std::uint64_t(1) << 30))
            ->capture_default_str();
        app->add_option("--max-cell-tests", max_cell_tests, "most cells voxelizing a mesh may test (an estimate)")
            ->check(CLI::Range(std::uint64_t(1), std::uint64_t(1) << 50))
            ->capture_default_str();
    }
};

// How results name a scene: a built-in by its spec, a file by its name.
inline std::string scene_label(const std::string& spec) {
    if (spec.rfind("builtin:", 0) == 0) return spec;
    return std::filesystem::path(spec).filename().string();
}

inline voxel_model load_scene(const std::string& spec, const scene_options& o) {
    auto start = std::chrono::steady_clock::now();
    std::fprintf(stderr, "loading %s ...\n", spec.c_str());
    voxel_model model;
    if (spec.rfind("builtin:", 0) == 0) {
        model = scenes::make_builtin(spec.substr(8));
    } else {
        std::filesystem::path path(spec);
        if (!std::filesystem::exists(path)) fail("scene file ", spec, " does not exist");
        auto ext = path.extension().string();
        if (ext == ".vox")
            model = io::load_vox(path, {.max_placed_voxels = o.max_voxels, .max_model_bytes = o.max_model_mib << 20});
        else if (gltf::is_coloured_mesh_path(path))  // coloured where the file has colour
            model = gltf::load_coloured_mesh_model(path, o.resolution, {.max_cell_tests = o.max_cell_tests});
        else
            fail("scene ", spec, ": unknown file type '", ext,
                 "' (expected .vox, .obj, .ply, .gltf, .glb or builtin:NAME)");
    }
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "loaded %s: %llu voxels in %.2f s\n", spec.c_str(),
                 (unsigned long long)model.voxel_count(), seconds);
    return model;
}

}  // namespace voxray::tool
