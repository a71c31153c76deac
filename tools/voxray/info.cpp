// voxray info SCENE...: per scene its extent, voxel count and colours used; per structure
// its size, build time and its own figures; with --json, the same as a results file
// (scripts/memory_table.py turns it into the README's memory table).
#include <bitset>
#include <cstdio>
#include <fstream>
#include <optional>

#include <nlohmann/json.hpp>

#include "bench_header.hpp"
#include "cli.hpp"
#include "engines.hpp"
#include "output.hpp"
#include "scene.hpp"

namespace voxray::tool {

namespace {

struct info_options {
    scene_options scene;
    std::string structures = structure_names(",");
    std::string json;
};

// One scene: the model's numbers, then each structure's, printed and (when open) written.
void describe(const std::string& spec, const info_options& o, std::ofstream& out) {
    auto model = load_scene(spec, o.scene);
    auto e = model.bounds().extent();
    std::bitset<256> used;  // palette entries that some voxel uses
    model.for_each_voxel([&](glm::ivec3, std::uint8_t v) { used.set(v); });
    std::printf("scene      %s\n", spec.c_str());
    std::printf("extent     %d x %d x %d\n", e.x, e.y, e.z);
    std::printf("voxels     %llu\n", (unsigned long long)model.voxel_count());
    std::printf("palette    %zu colours used\n", used.count());
    std::printf("%-14s %14s %12s %10s\n", "structure", "bytes", "bytes/voxel", "build s");
    for (auto& name : split_names(o.structures)) {
        std::fprintf(stderr, "building %s ...\n", name.c_str());
        auto s = build_structure(name, model);
        double per_voxel = model.voxel_count() ? double(s->bytes()) / double(model.voxel_count()) : 0.0;
        std::printf("%-14s %14zu %12.2f %10.3f\n", name.c_str(), s->bytes(), per_voxel, s->build_seconds());
        nlohmann::json figures = nlohmann::json::object();
        for (auto& [figure, value] : s->figures()) {
            std::printf("    %-20s %.6g\n", figure, value);
            figures[figure] = value;
        }
        if (out.is_open())
            out << nlohmann::json{{"type", "row"},           {"scene", scene_label(spec)},
                                  {"structure", name},       {"voxels", model.voxel_count()},
                                  {"bytes", s->bytes()},     {"bytes_per_voxel", per_voxel},
                                  {"build_seconds", s->build_seconds()}, {"figures", figures}}
                       .dump()
                << "\n";
    }
}

}  // namespace

command add_info(CLI::App& parent) {
    auto* app = parent.add_subcommand("info", "extent, voxels, colours; size, build time and figures of each structure");
    auto o = std::make_shared<info_options>();
    o->scene.add_to(app, true);
    app->add_option("--structures", o->structures, "structures to build")
        ->check(names_from(all_structure_names(), "structure"))
        ->capture_default_str();
    app->add_option("--json", o->json, "also write a results file: a header line, then one JSON line per structure");
    return {app, [o] {
        std::optional<output_file> file;
        std::ofstream none;  // not open: describe() writes no JSON to it
        if (!o->json.empty()) {
            file.emplace(o->json, "--json");
            file->stream() << results_header(own_command_line(), build_structure("dense", voxel_model{})->trace_on("cpu")->simd_width()).dump()
                           << "\n";
        }
        for (auto& spec : o->scene.scenes) describe(spec, *o, file ? file->stream() : none);
        if (file) file->finish();
        return 0;
    }};
}

}  // namespace voxray::tool
