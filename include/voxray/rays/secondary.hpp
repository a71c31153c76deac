// Rays that start where another ray hit: shadow rays towards a light and diffuse bounces,
// one at a time or for a whole batch of hits.
//
//   tracer.closest_hit(primary, hits);
//   auto shadow = voxray::shadow_rays(primary, hits, sun);     // misses get an inactive ray
//   tracer.any_hit(shadow, shadow_hits);                       // a hit: the point is in shadow
//   auto bounce = voxray::diffuse_rays(primary, hits, seed);
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include <glm/geometric.hpp>

#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/rays/sampling.hpp"

namespace voxray {

// Distance a new ray starts off the hit face (voxels): far above float rounding at the
// hit point for worlds up to ~10^4 voxels across, far below a voxel.
inline constexpr float hit_offset = 1e-3f;

// A ray every backend skips (tmin > tmax): it misses and costs no steps. Batches keep
// one ray per pixel this way, so hits stay index-aligned with the pixels.
inline ray inactive_ray() {
    ray r;
    r.tmin = 1.0f;
    r.tmax = 0.0f;
    return r;
}

// Whether a hit can start a new ray: a hit entered through a face. A ray that started
// inside solid (face::inside) has no face to leave from.
inline bool has_surface(const hit& h) { return h.is_hit() && h.normal != face::inside; }

// A point just off the hit face, so that a new ray from it does not start inside the
// voxel it left.
inline glm::vec3 offset_hit_point(const ray& r, const hit& h) {
    glm::vec3 p = r.origin + r.direction * h.t;
    return p + face_normal(h.normal) * hit_offset;
}

// From the hit towards a directional light (`to_light` need not be normalized); an
// inactive ray where there is no surface.
inline ray shadow_ray(const ray& r, const hit& h, glm::vec3 to_light) {
    if (!has_surface(h)) return inactive_ray();
    ray s;
    s.origin = offset_hit_point(r, h);
    s.direction = glm::normalize(to_light);
    return s;
}

// A cosine-weighted diffuse bounce off the hit face; an inactive ray where there is no
// surface (it then draws no random numbers).
inline ray diffuse_ray(const ray& r, const hit& h, rng& g) {
    if (!has_surface(h)) return inactive_ray();
    float u1 = g.uniform(), u2 = g.uniform();
    ray d;
    d.origin = offset_hit_point(r, h);
    d.direction = cosine_hemisphere(face_normal(h.normal), u1, u2);
    return d;
}

inline std::vector<ray> shadow_rays(std::span<const ray> primary, std::span<const hit> hits, glm::vec3 to_light) {
    std::vector<ray> rays(primary.size());
    for (std::size_t i = 0; i < primary.size(); ++i) rays[i] = shadow_ray(primary[i], hits[i], to_light);
    return rays;
}

// Diffuse bounces from every hit, seeded: the same seed gives the same rays everywhere.
inline std::vector<ray> diffuse_rays(std::span<const ray> primary, std::span<const hit> hits, std::uint64_t seed) {
    rng g(seed);
    std::vector<ray> rays(primary.size());
    for (std::size_t i = 0; i < primary.size(); ++i) rays[i] = diffuse_ray(primary[i], hits[i], g);
    return rays;
}

}  // namespace voxray
