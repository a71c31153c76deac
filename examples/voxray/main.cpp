// voxray: info, render, check and bench on any scene, structure and backend.
#include <cstdio>
#include <cstring>
#include <exception>
#include <string>

#include "commands.hpp"
#include "voxray/core/error.hpp"

namespace {

void usage() {
    std::puts(
        "usage: voxray <command> SCENE [options]\n"
        "  SCENE: a .vox, .obj or .ply file (meshes take --resolution N, default 512), or builtin:NAME\n"
        "         (builtin:terrain, builtin:menger; see README)\n"
        "commands:\n"
        "  info   SCENE [--structures A,B]\n"
        "  render SCENE --structure S --backend B --out FILE.png [--width W --height H] [--view V]\n"
        "  check  SCENE [--rays N] [--structures A,B] [--backends A,B] [--seed K] [--edits K]\n"
        "  bench  SCENE --structure S --backend B [--rays primary|secondary|shadow]\n"
        "         [--width W --height H] [--runs R] [--json FILE]\n"
        "  bench  SCENE --structure brickmap --backend B --edits spheres|voxel [--threads T] [--runs FRAMES]\n"
        "structures: dense, brickmap, embree-quads, embree-boxes    backends: cpu, cpu-scalar, opencl, vulkan");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 2 || !std::strcmp(argv[1], "--help") || !std::strcmp(argv[1], "-h")) {
        usage();
        return argc < 2 ? 2 : 0;
    }
    std::string command = argv[1];
    try {
        if (command == "info") return voxray::tool::run_info(argc, argv);
        if (command == "render") return voxray::tool::run_render(argc, argv);
        if (command == "check") return voxray::tool::run_check(argc, argv);
        if (command == "bench") return voxray::tool::run_bench(argc, argv);
        std::fprintf(stderr, "voxray: unknown command '%s'\n", command.c_str());
        usage();
        return 2;
    } catch (const voxray::error& e) {
        std::fprintf(stderr, "voxray %s: error: %s\n", command.c_str(), e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "voxray %s: unexpected error: %s\n", command.c_str(), e.what());
        return 1;
    }
}
