// What one voxel's sampling rays see of the original surface (the paper's section 3.2):
// each ray's first hit inside the voxel, against any triangle. A front-facing hit (or any
// hit on a double-sided material) gives a sample: the surface's normal turned towards the
// ray, and its colour there (io/mesh_surface.hpp). A back-facing hit on a one-sided
// material occludes without a sample. A hit where the alpha rule cuts the surface out
// (leaf cards) lets the ray go on. A miss is a ray that passes.
//
// `Scene` traces the mesh in voxel space: first_hit(origin, direction, tnear, tfar) returning
// an optional hit with t, triangle, barycentric and unit normal (embree/triangle_scene.hpp).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "voxray/appearance/sampling_rays.hpp"
#include "voxray/appearance/voxel_triangles.hpp"
#include "voxray/io/mesh.hpp"

namespace voxray::appearance {

struct sampling_options {
    std::uint32_t rays = 150;  // per voxel, as in the paper
    bool stratified = true;    // spherical Fibonacci directions (false: independent uniform ones)
    std::uint64_t seed = 1;
};

struct surface_sample {
    glm::vec3 normal{0, 0, 1};  // unit, facing the ray
    glm::vec4 colour{1.0f};     // linear RGBA
};

// One sampling ray's outcome: its direction, whether it stopped inside the voxel, and its
// sample in `seen` (or -1: a miss, or a surface seen from behind).
struct ray_outcome {
    glm::vec3 direction{0.0f};
    bool hit = false;
    std::int32_t sample = -1;
};

struct voxel_samples {
    std::vector<surface_sample> seen;
    std::vector<ray_outcome> outcomes;  // one a ray, in ray order
    std::uint32_t rays = 0, hits = 0;   // hits: rays stopped inside the voxel (samples or occlusion)
};

// Steps over a cut-out surface before a ray gives up (an alpha-tested stack of cards).
inline constexpr int max_cut_out_layers = 64;

// What a ray segment inside a voxel meets first: nothing, a surface that only occludes
// (seen from behind, one-sided), or a sample.
struct segment_hit {
    bool hit = false, sample = false;
    float t = 0;         // from the segment's origin, when it hit
    float coverage = 0;  // how much of the ray stopped: 1 on a triangle, 0..1 on filtered voxels
    surface_sample seen;
};

// The first surface along the segment from `origin` (on the voxel's surface) for `length`;
// without `with_colour`, only whether and where it stops (the sample's colour left white).
template <class Scene>
segment_hit first_surface(const Scene& scene, const io::triangle_mesh& mesh, glm::dvec3 origin, glm::dvec3 direction,
                          double length, bool with_colour = true) {
    const io::mesh_surface& s = mesh.surface;
    constexpr float margin = 1e-4f;  // surfaces on the voxel's own faces count, from both sides
    glm::vec3 dir(direction), org = glm::vec3(origin) - margin * dir;  // Embree wants tnear >= 0
    float tnear = 0.0f, tfar = float(length) + 2.0f * margin;
    for (int layer = 0; layer < max_cut_out_layers; ++layer) {
        auto hit = scene.first_hit(org, dir, tnear, tfar);
        if (!hit) break;
        glm::vec4 colour(1.0f);
        bool double_sided = false;
        if (s.coloured()) {
            const io::mesh_material& m = s.materials[s.triangle_materials[hit->triangle]];
            colour = with_colour ? s.colour_at(hit->triangle, hit->barycentric)
                                 : glm::vec4(1.0f, 1.0f, 1.0f, s.alpha_at(hit->triangle, hit->barycentric));
            double_sided = m.double_sided;
            if (m.cuts() && colour.a < m.cutoff()) {  // cut out here: go on behind it
                tnear = hit->t + std::max(margin, hit->t * 0x1.0p-18f);
                continue;
            }
        }
        bool front = glm::dot(hit->normal, dir) < 0.0f;
        segment_hit out;
        out.hit = true, out.sample = front || double_sided, out.t = hit->t - margin, out.coverage = 1.0f;
        out.seen = {front ? hit->normal : -hit->normal, colour};
        return out;
    }
    return {};
}

// What the sampling rays of a table meet: the original triangles. (A coarser level's rays
// meet the finer level's filtered voxels instead: appearance/resample.hpp.) Any type with
// this first_surface and coverage does; the voxel space is the table's.
template <class Scene>
struct triangle_surfaces {
    const Scene& scene;
    const io::triangle_mesh& mesh;

    segment_hit first_surface(glm::dvec3 origin, glm::dvec3 direction, double length) const {
        return appearance::first_surface(scene, mesh, origin, direction, length);
    }
    // How much of the segment's ray stops (first_surface's coverage, its colour not looked up).
    float coverage(glm::dvec3 origin, glm::dvec3 direction, double length) const {
        return appearance::first_surface(scene, mesh, origin, direction, length, false).coverage;
    }

    // Calls use(surfaces) with these surfaces as the rays of `voxel` meet them: its own
    // triangles (a voxel_triangles scene) through `scratch` where the scene can list them and
    // they are few, else the whole scene. The hits are the same either way.
    template <class Use>
    void for_voxel(glm::ivec3 voxel, voxel_triangles& scratch, Use&& use) const {
        if constexpr (requires(std::vector<std::uint32_t>& out) {
                          scene.triangles_near(glm::vec3(0.0f), 1.0f, out);
                          scene.corners(0u);
                      }) {
            if (scratch.gather(scene, voxel)) return use(triangle_surfaces<voxel_triangles>{scratch, mesh});
        }
        use(*this);
    }
};
// Spelled out for compilers without deduction for aggregates (clang before 17).
template <class Scene>
triangle_surfaces(const Scene&, const io::triangle_mesh&) -> triangle_surfaces<Scene>;

// use(surfaces narrowed to `voxel`) where `surfaces` can narrow (triangle_surfaces::for_voxel),
// else use(surfaces).
template <class Surfaces, class Use>
void with_voxel_surfaces(const Surfaces& surfaces, glm::ivec3 voxel, voxel_triangles& scratch, Use&& use) {
    if constexpr (requires { surfaces.for_voxel(voxel, scratch, use); })
        surfaces.for_voxel(voxel, scratch, use);
    else
        use(surfaces);
}

template <class Surfaces>
void sample_voxel(const Surfaces& surfaces, glm::ivec3 voxel, const sampling_options& o, voxel_samples& out) {
    out.seen.clear();
    out.outcomes.clear();
    out.rays = o.rays, out.hits = 0;
    const voxel_rays rays(voxel, o.rays, o.stratified, o.seed);
    for (std::uint32_t i = 0; i < o.rays; ++i) {
        sampling_ray ray = rays(i);
        segment_hit h = surfaces.first_surface(ray.origin, ray.direction, ray.length);
        out.hits += h.hit ? 1u : 0u;
        out.outcomes.push_back({glm::vec3(ray.direction), h.hit, h.sample ? std::int32_t(out.seen.size()) : -1});
        if (h.sample) out.seen.push_back(h.seen);
    }
}

}  // namespace voxray::appearance
