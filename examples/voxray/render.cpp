// voxray render: palette colour, one directional light with a shadow ray, sky on a miss.
#include <algorithm>
#include <cstdio>

#include "args.hpp"
#include "commands.hpp"
#include "engines.hpp"
#include "png_writer.hpp"
#include "scene.hpp"
#include "voxray/check/ray_sets.hpp"

namespace voxray::tool {

// The light comes from above and to the side, whatever the scene's up axis.
glm::vec3 light_direction(int up_axis) {
    glm::vec3 l(0.0f);
    l[up_axis] = 0.8f;
    l[(up_axis + 1) % 3] = 0.45f;
    l[(up_axis + 2) % 3] = 0.35f;
    return glm::normalize(l);
}

int run_render(int argc, char** argv) {
    args a(argc, argv, 2, {"structure", "backend", "out", "width", "height", "view", "resolution"});
    if (a.positional().size() != 1) fail("render takes one SCENE");
    if (!a.has("out")) fail("render needs --out FILE.png");
    int width = int(a.number("width", 1280, 1, 16384)), height = int(a.number("height", 720, 1, 16384));
    auto model = load_scene(a.positional()[0], int(a.number("resolution", 512, 1, 4096)));
    auto structure = build_structure(a.get("structure", "dense"), model);
    auto engine = structure->trace_on(a.get("backend", "cpu"));

    std::fprintf(stderr, "tracing %d x %d on %s / %s ...\n", width, height, structure->name().c_str(), engine->device().c_str());
    auto cam = auto_camera(model.bounds(), model.up_axis, int(a.number("view", 0, 0, 7)));
    auto rays = primary_rays(cam, width, height);
    std::vector<hit> hits(rays.size()), shadow(rays.size());
    engine->closest_hit(rays, hits);
    glm::vec3 light = light_direction(model.up_axis);
    auto shadow_set = shadow_rays(rays, hits, light);
    engine->any_hit(shadow_set, shadow);

    std::vector<std::uint8_t> rgb(rays.size() * 3);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        glm::vec3 c;
        if (hits[i].is_hit()) {
            auto col = model.palette()[std::uint8_t(hits[i].material)].colour;
            glm::vec3 albedo = glm::vec3(col.r, col.g, col.b) / 255.0f;
            float lambert = std::max(0.0f, glm::dot(face_normal(hits[i].normal), light));
            float lit = shadow[i].is_hit() ? 0.0f : lambert;
            c = albedo * (0.3f + 0.7f * lit);
        } else {
            float up = std::clamp(rays[i].direction[model.up_axis] * 0.5f + 0.5f, 0.0f, 1.0f);
            c = glm::mix(glm::vec3(0.85f, 0.88f, 0.92f), glm::vec3(0.45f, 0.62f, 0.86f), up);
        }
        for (int k = 0; k < 3; ++k)
            rgb[i * 3 + k] = std::uint8_t(std::clamp(std::pow(c[k], 1.0f / 2.2f), 0.0f, 1.0f) * 255.0f + 0.5f);
    }
    write_png(a.get("out", ""), width, height, rgb);
    std::printf("wrote %s (%d x %d, %s on %s)\n", a.get("out", "").c_str(), width, height, structure->name().c_str(),
                a.get("backend", "cpu").c_str());
    return 0;
}

}  // namespace voxray::tool
