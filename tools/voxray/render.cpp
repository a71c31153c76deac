// voxray render: palette colour, one directional light with a shadow ray, sky on a miss.
// The camera is one of 8 preset views around the scene, or free (--eye, --target, --fov).
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "cli.hpp"
#include "engines.hpp"
#include "entity_scene.hpp"
#include "image_writer.hpp"
#include "scene.hpp"
#include "voxray/rays.hpp"

namespace voxray::tool {

namespace {

struct render_options {
    scene_options scene;
    std::string structure = "dense", backend = "cpu", out;
    int width = 1280, height = 720, view = 0;
    std::vector<float> eye, target;
    float fov = 50.0f;
    int frames = 1;
};

// Rays, hits, shadow rays and shadow hits, and the image: what a pixel costs.
constexpr std::uint64_t bytes_per_pixel = 2 * sizeof(ray) + 2 * sizeof(hit) + 3;

camera choose_camera(const render_options& o, const voxel_model& model) {
    if (o.eye.empty()) return auto_camera(model.bounds(), model.up_axis, o.view);
    box3i b = model.bounds();
    glm::vec3 eye(o.eye[0], o.eye[1], o.eye[2]);
    glm::vec3 target = o.target.empty() ? (glm::vec3(b.min) + glm::vec3(b.max)) * 0.5f : glm::vec3(o.target[0], o.target[1], o.target[2]);
    if (!(glm::length(target - eye) > 0.0f)) fail("--eye and --target are the same point");
    glm::vec3 up(0.0f);
    up[model.up_axis] = 1.0f;
    return look_at(eye, target, o.fov, up);
}

int render(const render_options& o) {
    require_image_path(o.out, "--out");
    require_writable(o.out, "--out");
    require_memory(bytes_per_pixel * std::uint64_t(o.width) * std::uint64_t(o.height),
                   "render " + std::to_string(o.width) + " x " + std::to_string(o.height) + " (" +
                       std::to_string(bytes_per_pixel) + " bytes a pixel)");
    if (is_scene_description(o.scene.scenes[0])) {
        if (!o.eye.empty()) fail("--eye: a scene file is rendered from the preset views (--view)");
        return render_scene_file(o.scene.scenes[0], o.scene, o.frames, o.structure, o.backend, o.width, o.height, o.view, o.out);
    }
    if (o.frames != 1) fail("--frames ", o.frames, ": only a scene file (.json) has frames");
    auto model = load_scene(o.scene.scenes[0], o.scene);
    std::fprintf(stderr, "building %s ...\n", o.structure.c_str());
    auto structure = build_structure(o.structure, model);
    auto engine = structure->trace_on(o.backend);

    std::fprintf(stderr, "tracing %d x %d on %s / %s ...\n", o.width, o.height, structure->name().c_str(), engine->device().c_str());
    auto rays = primary_rays(choose_camera(o, model), o.width, o.height);
    std::vector<hit> hits(rays.size()), shadow(rays.size());
    engine->closest_hit(rays, hits);
    glm::vec3 sun = sun_direction(model.up_axis);
    auto shadow_set = shadow_rays(rays, hits, sun);
    engine->any_hit(shadow_set, shadow);

    std::vector<std::uint8_t> rgb(rays.size() * 3);
    bool colours = structure->colour_tolerance().has_value();  // hits carry colours, not palette indices
    for (std::size_t i = 0; i < rays.size(); ++i) {
        glm::vec3 albedo_of_hit = colours ? albedo_rgba8(hits[i]) : albedo(model.palette(), hits[i]);
        glm::vec3 c = hits[i].is_hit() ? shade(albedo_of_hit, hits[i], sun, shadow[i].is_hit())
                                       : sky(rays[i].direction, model.up_axis);
        auto px = to_srgb8(c);
        std::copy(px.begin(), px.end(), rgb.begin() + i * 3);
    }
    write_image(o.out, o.width, o.height, rgb);
    std::printf("wrote %s (%d x %d, %s on %s)\n", o.out.c_str(), o.width, o.height, structure->name().c_str(), o.backend.c_str());
    return 0;
}

}  // namespace

command add_render(CLI::App& parent) {
    auto* app = parent.add_subcommand("render", "render an image: palette colours, a sun with shadows, sky");
    auto o = std::make_shared<render_options>();
    o->scene.add_to(app, false);
    app->add_option("--structure", o->structure, "structure to trace")
        ->check(CLI::IsMember(all_structure_names()))->capture_default_str();
    app->add_option("--backend", o->backend, "backend to trace on")->check(CLI::IsMember(backend_names()))->capture_default_str();
    app->add_option("--out", o->out, "image to write: .png, .jpg, .bmp or .tga")->required();
    app->add_option("--width", o->width, "image width")->check(CLI::Range(1, 16384))->capture_default_str();
    app->add_option("--height", o->height, "image height")->check(CLI::Range(1, 16384))->capture_default_str();
    auto* view = app->add_option("--view", o->view, "preset view around the scene")->check(CLI::Range(0, 7))->capture_default_str();
    auto* eye = app->add_option("--eye", o->eye, "free camera position X,Y,Z (voxel units)")
                    ->expected(3)->delimiter(',')->excludes(view);
    app->add_option("--target", o->target, "point the free camera looks at (default: the scene's centre)")
        ->expected(3)->delimiter(',')->needs(eye);
    app->add_option("--fov", o->fov, "free camera's vertical field of view, degrees")
        ->check(finite_range(1.0, 179.0))->needs(eye)->capture_default_str();
    app->add_option("--frames", o->frames, "frames of a scene file's motion, one image each (NAME_000.png ...)")
        ->check(CLI::Range(1, 100000))->capture_default_str();
    return {app, [o] { return render(*o); }};
}

}  // namespace voxray::tool
