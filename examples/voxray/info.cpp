// voxray info SCENE: extent, voxel count, palette; per structure its size and build time.
#include <cstdio>

#include "args.hpp"
#include "commands.hpp"
#include "engines.hpp"
#include "scene.hpp"

namespace voxray::tool {

int run_info(int argc, char** argv) {
    args a(argc, argv, 2, {"structures", "resolution"});
    if (a.positional().size() != 1) fail("info takes one SCENE");
    auto model = load_scene(a.positional()[0], int(a.number("resolution", 512, 1, 4096)));
    auto e = model.bounds().extent();
    std::printf("scene      %s\n", a.positional()[0].c_str());
    std::printf("extent     %d x %d x %d\n", e.x, e.y, e.z);
    std::printf("voxels     %llu\n", (unsigned long long)model.voxel_count());
    std::printf("palette    %d colours used\n", model.palette().used_entries());
    std::printf("%-14s %14s %12s %10s\n", "structure", "bytes", "bytes/voxel", "build s");
    for (auto& name : a.list("structures", structure_names(","))) {
        std::fprintf(stderr, "building %s ...\n", name.c_str());
        auto s = build_structure(name, model);
        double per_voxel = model.voxel_count() ? double(s->bytes()) / double(model.voxel_count()) : 0.0;
        std::printf("%-14s %14zu %12.2f %10.3f\n", name.c_str(), s->bytes(), per_voxel, s->build_seconds());
    }
    return 0;
}

}  // namespace voxray::tool
