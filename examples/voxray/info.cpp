// voxray info SCENE: extent, voxel count, colours used; per structure its size and build time.
#include <bitset>
#include <cstdio>

#include "cli.hpp"
#include "engines.hpp"
#include "scene.hpp"

namespace voxray::tool {

command add_info(CLI::App& parent) {
    auto* app = parent.add_subcommand("info", "extent, voxels, colours; size and build time of each structure");
    auto scene = std::make_shared<scene_options>();
    auto structures = std::make_shared<std::string>(structure_names(","));
    scene->add_to(app, false);
    app->add_option("--structures", *structures, "structures to build")
        ->check(names_from(all_structure_names(), "structure"))
        ->capture_default_str();
    return {app, [=] {
        auto model = load_scene(scene->scenes[0], *scene);
        auto e = model.bounds().extent();
        std::bitset<256> used;  // palette entries that some voxel uses
        model.for_each_voxel([&](glm::ivec3, std::uint8_t v) { used.set(v); });
        std::printf("scene      %s\n", scene->scenes[0].c_str());
        std::printf("extent     %d x %d x %d\n", e.x, e.y, e.z);
        std::printf("voxels     %llu\n", (unsigned long long)model.voxel_count());
        std::printf("palette    %zu colours used\n", used.count());
        std::printf("%-14s %14s %12s %10s\n", "structure", "bytes", "bytes/voxel", "build s");
        for (auto& name : split_names(*structures)) {
            std::fprintf(stderr, "building %s ...\n", name.c_str());
            auto s = build_structure(name, model);
            double per_voxel = model.voxel_count() ? double(s->bytes()) / double(model.voxel_count()) : 0.0;
            std::printf("%-14s %14zu %12.2f %10.3f\n", name.c_str(), s->bytes(), per_voxel, s->build_seconds());
            for (auto& [figure, value] : s->figures()) std::printf("    %-20s %.6g\n", figure, value);
        }
        return 0;
    }};
}

}  // namespace voxray::tool
