// voxray: info, render, check and bench on any scene, structure and backend; world-build
// and world-fly for open worlds on disk.
#include <cstdio>
#include <exception>
#include <string>

#include "cli.hpp"
#include "voxray/core/error.hpp"
#include "voxray/version.hpp"

int main(int argc, char** argv) {
    using namespace voxray::tool;
    CLI::App app{"voxray: voxel ray tracing structures x backends on any scene.\n"
                 "SCENE: a .vox, .obj or .ply file (meshes take --resolution) or builtin:NAME[:SIZE] "
                 "(builtin:terrain, builtin:menger; one 64^3 chunk: builtin:sphere30, checker, noise50, terrain64)"};
    app.require_subcommand(1);  // --version answers without one
    app.set_help_all_flag("--help-all", "help for every command");
    app.set_version_flag("--version", std::string("voxray ") + VOXRAY_VERSION_STRING);
    std::vector<command> commands = {add_info(app),  add_render(app),      add_check(app),
                                     add_bench(app), add_world_build(app), add_world_fly(app),
                                     add_mesh(app),  add_mesh_bench(app), add_appearance_bench(app),
                                     add_appearance_world_bench(app), add_appearance_walk_bench(app)};
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return app.exit(e);
    }
    for (auto& c : commands) {
        if (!c.app->parsed()) continue;
        try {
            return c.run();
        } catch (const voxray::error& e) {
            std::fprintf(stderr, "voxray %s: error: %s\n", c.app->get_name().c_str(), e.what());
            return 1;
        } catch (const std::exception& e) {
            std::fprintf(stderr, "voxray %s: unexpected error: %s\n", c.app->get_name().c_str(), e.what());
            return 1;
        }
    }
    return 2;
}
