// Load a .vox, build a brickmap, trace camera and shadow rays, shade, write a PNG: the
// whole path an engine takes, with the public helpers of voxray/rays.hpp.
//
//   voxray_example_render_vox scene.vox out.png [width height]
//
// Swapping voxray::cpu for voxray::opencl or voxray::vulkan (and linking that target)
// renders the same image on a GPU backend. `voxray render SCENE --structure brickmap`
// uses the same helpers and gives the same bytes.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <vector>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include "voxray/brickmap/brickmap.hpp"
#include "voxray/cpu.hpp"
#include "voxray/io/vox_reader.hpp"
#include "voxray/rays.hpp"

int main(int argc, char** argv) try {
    if (argc != 3 && argc != 5) {
        std::fprintf(stderr, "usage: %s scene.vox out.png [width height]\n", argv[0]);
        return 2;
    }
    int width = argc == 5 ? std::atoi(argv[3]) : 640, height = argc == 5 ? std::atoi(argv[4]) : 360;

    // 1. Load and build. The tracer keeps its own copy of the structure's data.
    voxray::voxel_model model = voxray::io::load_vox(argv[1]);
    voxray::brickmap<> world(model);
    voxray::tracer<voxray::cpu, voxray::brickmap<>> tracer(world);

    // 2. Camera rays, then shadow rays from every hit towards the sun.
    voxray::camera cam = voxray::auto_camera(model.bounds(), model.up_axis);  // or look_at(eye, target, fov)
    std::vector<voxray::ray> rays = voxray::primary_rays(cam, width, height);
    std::vector<voxray::hit> hits(rays.size()), shadow_hits(rays.size());
    tracer.closest_hit(rays, hits);
    glm::vec3 sun = voxray::sun_direction(model.up_axis);
    std::vector<voxray::ray> shadow = voxray::shadow_rays(rays, hits, sun);  // misses: inactive rays
    tracer.any_hit(shadow, shadow_hits);

    // 3. Shade: palette colour, sun and shadow; sky where the ray missed.
    std::vector<std::uint8_t> rgb;
    std::size_t hit_pixels = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        glm::vec3 c = hits[i].is_hit() ? voxray::shade(model.palette(), hits[i], sun, shadow_hits[i].is_hit())
                                       : voxray::sky(rays[i].direction, model.up_axis);
        hit_pixels += hits[i].is_hit();
        for (std::uint8_t v : voxray::to_srgb8(c)) rgb.push_back(v);
    }

    // 4. Write the PNG (stb_image_write, Debian: libstb-dev).
    if (!stbi_write_png(argv[2], width, height, 3, rgb.data(), width * 3)) {
        std::fprintf(stderr, "cannot write %s\n", argv[2]);
        return 1;
    }
    std::printf("wrote %s: %d x %d, %zu pixels hit the scene\n", argv[2], width, height, hit_pixels);
    return hit_pixels > 0 ? 0 : 1;
} catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
}
