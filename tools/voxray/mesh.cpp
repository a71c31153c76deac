// voxray mesh: a scene as POP chunk meshes. Prints statistics per level of detail (quads
// drawn, overdraw before and after the squashed-face pass) and per chunk, and exports the
// quads drawn at one level to PLY or glTF 2.0.
#include <cstdio>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "mesh_export.hpp"
#include "mesh_raster.hpp"
#include "mesh_scene.hpp"
#include "output.hpp"
#include "scene.hpp"
#include "units.hpp"

namespace voxray::tool {

namespace {

struct mesh_options {
    scene_options scene;
    bool ao = false, keep_squashed = false, per_chunk = false;
    unsigned threads = 2;
    int level = 0;
    std::string ply, gltf, json;
    raster_options raster;
};

int mesh(const mesh_options& o) {
    for (auto* path : {&o.ply, &o.gltf, &o.json, &o.raster.png})
        if (!path->empty()) require_writable(*path, "output");
    if (!o.raster.png.empty()) require_image_path(o.raster.png, "--png");
    voxel_model model = load_scene(o.scene.scenes[0], o.scene);
    meshing::mesher_options options{.ambient_occlusion = o.ao};
    auto plain = mesh_scene(model, options, false, o.threads);
    auto scene = o.keep_squashed ? plain : mesh_scene(model, options, true, o.threads);
    std::uint64_t faces = 0, quads = 0, bytes = 0;
    for (auto& m : scene.meshes) faces += covered_faces(m), quads += m.quad_count(), bytes += m.bytes();
    std::printf("%s: %zu chunks, %llu faces -> %llu quads (%.2f faces a quad), %s, meshed in %s on %u threads\n",
                scene_label(o.scene.scenes[0]).c_str(), scene.meshes.size(), (unsigned long long)faces,
                (unsigned long long)quads, quads ? double(faces) / double(quads) : 0.0, human_bytes(double(bytes)).c_str(),
                human_seconds(plain.seconds).c_str(), o.threads);

    nlohmann::json levels = nlohmann::json::array();
    std::printf("%5s %10s %10s %12s %12s\n", "level", "quads", "triangles", "overdraw", o.keep_squashed ? "" : "(before pass)");
    for (int level = 0; level < VX_MESH_LEVELS; ++level) {
        auto after = figures_at(scene.meshes, level), before = figures_at(plain.meshes, level);
        std::printf("%5d %10llu %10llu %12.3f %12.3f\n", level, (unsigned long long)after.quads,
                    (unsigned long long)after.quads * 2, after.overdraw.ratio(), before.overdraw.ratio());
        levels.push_back({{"level", level}, {"quads", after.quads}, {"overdraw", after.overdraw.ratio()},
                          {"quads_before_squashed", before.quads}, {"overdraw_before_squashed", before.overdraw.ratio()}});
    }
    nlohmann::json chunks = nlohmann::json::array();
    bool print_chunks = o.per_chunk || scene.meshes.size() <= 8;
    if (print_chunks) std::printf("%-22s %8s %8s  quads drawn at levels 0..6\n", "chunk origin", "faces", "quads");
    for (auto& m : scene.meshes) {
        nlohmann::json drawn = nlohmann::json::array();
        std::string drawn_text;
        for (int level = 0; level < VX_MESH_LEVELS; ++level) {
            drawn.push_back(m.drawn(level));
            drawn_text.push_back(' ');
            drawn_text.append(std::to_string(m.drawn(level)));
        }
        chunks.push_back({{"origin", {m.origin.x, m.origin.y, m.origin.z}}, {"faces", covered_faces(m)}, {"quads", m.quad_count()},
                          {"drawn", drawn}});
        if (print_chunks)
            std::printf("(%6d, %6d, %6d) %8llu %8u %s\n", m.origin.x, m.origin.y, m.origin.z,
                        (unsigned long long)covered_faces(m), m.quad_count(), drawn_text.c_str());
    }
    if (!o.raster.png.empty()) write_raster_png(model, scene.meshes, o.raster);
    if (!o.ply.empty()) write_mesh_ply(o.ply, scene.meshes, model.palette(), o.level);
    if (!o.gltf.empty()) write_mesh_gltf(o.gltf, scene.meshes, model.palette(), o.level);
    if (!o.json.empty()) {
        output_file out(o.json, "--json");
        out.stream() << nlohmann::json{{"scene", scene_label(o.scene.scenes[0])}, {"faces", faces}, {"quads", quads},
                                       {"bytes", bytes}, {"levels", levels}, {"chunks", chunks}}.dump(1)
                     << "\n";
        out.finish();
    }
    return 0;
}

}  // namespace

command add_mesh(CLI::App& parent) {
    auto* app = parent.add_subcommand("mesh", "a scene as POP chunk meshes: statistics per level and chunk, PLY and glTF export");
    auto o = std::make_shared<mesh_options>();
    o->scene.add_to(app, false);
    app->add_flag("--ao", o->ao, "ambient occlusion per quad corner (merging stops where it differs)");
    app->add_flag("--keep-squashed", o->keep_squashed, "skip the squashed-face pass");
    app->add_flag("--per-chunk", o->per_chunk, "print every chunk (else only up to 8)");
    app->add_option("--threads", o->threads, "meshing threads")->check(CLI::Range(1u, 256u))->capture_default_str();
    app->add_option("--level", o->level, "level of detail the exports draw")->check(CLI::Range(0, VX_MESH_LEVELS - 1))->capture_default_str();
    app->add_option("--ply", o->ply, "write the quads drawn at --level to this PLY file");
    app->add_option("--gltf", o->gltf, "write them to this glTF 2.0 file (.glb: binary)");
    app->add_option("--json", o->json, "write the statistics to this JSON file");
    app->add_option("--png", o->raster.png, "draw the meshes with the Vulkan raster path to this image");
    app->add_option("--lod-bias", o->raster.lod_bias, "--png: t = log2(distance) - bias; 64 draws level 0 everywhere")
        ->capture_default_str();
    app->add_option("--width", o->raster.width, "--png: pixels")->check(CLI::Range(1, 16384))->capture_default_str();
    app->add_option("--height", o->raster.height, "--png: pixels")->check(CLI::Range(1, 16384))->capture_default_str();
    app->add_option("--view", o->raster.view, "--png: the camera, as voxray render --view")
        ->check(CLI::Range(0, 7))
        ->capture_default_str();
    return {app, [o] { return mesh(*o); }};
}

}  // namespace voxray::tool
