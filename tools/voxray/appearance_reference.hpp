// The reference pictures of appearance-bench: the original triangles traced by Embree at
// many stratified samples a pixel, shaded as the appearance records are (appearance/record.h):
// colour * (ambient + (1 - ambient) * max(0, n . l)), with the normal turned to the viewer on
// double-sided materials, black on the back of one-sided ones, and the background where a
// ray meets nothing. Cut-outs let rays through, as in the precompute. With `shadows`, a
// point whose shadow ray towards the light meets a triangle (cut-outs let it through) gets
// the ambient alone: the truth the precomputed shadows (appearance/shadows.hpp) approximate.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "voxray/appearance/voxel_sampler.hpp"
#include "voxray/model/build_threads.hpp"
#include "voxray/rays/camera.hpp"

namespace voxray::tool {

struct shading {
    glm::vec3 to_light{0, 1, 0};  // unit
    float ambient = 0.2f;
    glm::vec3 background{0.2f};   // linear
    bool shadows = false;         // cast shadows (the methods then walk precomputed ones)
};

// A linear RGB picture, and the share of each pixel's samples that met a surface.
struct linear_picture {
    int width = 0, height = 0;
    std::vector<glm::vec3> rgb;
    std::vector<float> coverage;
};

// The colour seen at `h`, the first surface along a ray from `origin` in `direction`.
template <class Scene>
glm::vec3 shade_surface(const Scene& scene, const io::triangle_mesh& mesh, const appearance::segment_hit& h,
                        const ray& r, const shading& s) {
    if (!h.hit) return s.background;
    if (!h.sample) return glm::vec3(0.0f);
    float lambert = std::max(glm::dot(h.seen.normal, s.to_light), 0.0f);
    if (s.shadows && lambert > 0.0f) {
        // From a thousandth of a voxel off the surface, on the side the light and the viewer are.
        glm::vec3 at = r.origin + h.t * r.direction + 1e-3f * h.seen.normal;
        if (appearance::first_surface(scene, mesh, glm::dvec3(at), glm::dvec3(s.to_light), 1e7).hit) lambert = 0.0f;
    }
    return glm::vec3(h.seen.colour) * (s.ambient + (1.0f - s.ambient) * lambert);
}

// Pictures of `mesh` (in voxel space, as `scene` traces it) seen by `cam`, one per shading,
// at side x side stratified samples a pixel.
template <class Scene>
std::vector<linear_picture> reference_pictures(const Scene& scene, const io::triangle_mesh& mesh, const camera& cam,
                                               int width, int height, int side, const std::vector<shading>& lights,
                                               unsigned threads) {
    camera_frame frame(cam, width, height);
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    linear_picture blank{width, height, std::vector<glm::vec3>(pixels, glm::vec3(0.0f)), {}};
    std::vector<linear_picture> out(lights.size(), blank);
    std::vector<float> coverage(pixels, 0.0f);
    const unsigned count = resolve_build_threads(threads, std::size_t(height));
    run_build_threads(count, [&](unsigned t) {  // rows t, t + count, ...
        for (int y = int(t); y < height; y += int(count))
            for (int x = 0; x < width; ++x) {
                std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
                std::uint32_t hits = 0;
                for (int sy = 0; sy < side; ++sy)
                    for (int sx = 0; sx < side; ++sx) {
                        // Jitter keyed by (pixel, sample), as the sampling rays are by (voxel, ray).
                        std::uint32_t key = std::uint32_t(sy * side + sx);
                        double jx = appearance::uniform01(7, {x, y, 0}, key, 0);
                        double jy = appearance::uniform01(7, {x, y, 0}, key, 1);
                        ray r = frame.through(float(x) + float((sx + jx) / side), float(y) + float((sy + jy) / side));
                        appearance::segment_hit h =
                            appearance::first_surface(scene, mesh, glm::dvec3(r.origin), glm::dvec3(r.direction), 1e7);
                        hits += h.hit ? 1u : 0u;
                        for (std::size_t l = 0; l < lights.size(); ++l)
                            out[l].rgb[i] += shade_surface(scene, mesh, h, r, lights[l]);
                    }
                for (auto& p : out) p.rgb[i] /= float(side * side);
                coverage[i] = float(hits) / float(side * side);
            }
    });
    for (auto& p : out) p.coverage = coverage;
    return out;
}

}  // namespace voxray::tool
