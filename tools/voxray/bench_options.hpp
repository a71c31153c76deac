// Options of `voxray bench` (the matrix and the edit benchmark share them).
#pragma once
#include <string>

#include "scene.hpp"

namespace voxray::tool {

struct bench_options {
    scene_options scene;
    std::string structures, backends, ray_sets;  // comma-separated
    std::string out, ray_file, write_rays, edits;
    std::string candidates;  // a scene file's ways to find candidate entities, comma-separated
    std::string pixel_order = "tiles";  // of the primary rays: rows or tiles (rays/camera.hpp)
    int width = 1920, height = 1080, runs = 5, warmup = 1;
    unsigned threads = 2;
};

int run_matrix(const bench_options& o);
int run_edit_bench(const bench_options& o);

}  // namespace voxray::tool
