// Scenes for the entity tests: real worlds and models from ../shared/data where present
// (procedural stand-ins otherwise), random poses with rotations of every kind, and
// the comparison against the brute-force reference (voxray/entities/reference.hpp).
#pragma once
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hit_bits.hpp"
#include "random_models.hpp"
#include "special_rays.hpp"
#include "test_data.hpp"
#include "voxray/core/type_list.hpp"
#include "voxray/entities/reference.hpp"
#include "voxray/generated/structures.hpp"
#include "voxray/io/vox_reader.hpp"
#include "voxray/rays/sampling.hpp"
#include "voxray/scenes/builtin.hpp"
#include "voxray/tracer.hpp"

namespace voxray::test {

// A shared .vox file by name, else the procedural stand-in.
inline voxel_model shared_or(const char* file, voxel_model fallback) {
    if (auto dir = data_dir(); dir && std::filesystem::exists(*dir / "vox" / file)) return io::load_vox(*dir / "vox" / file);
    return fallback;
}

inline voxel_model test_world() { return shared_or("bevy_test.vox", scenes::make_builtin("terrain:64", 2)); }

// Entity models: a real one (a deer), a sparse 12^3 noise cube and a 40^3 hollow box (larger
// than a 16^3 chunk).
inline std::vector<voxel_model> test_models() {
    std::vector<voxel_model> models;
    models.push_back(shared_or("bevy_deer_v200.vox", sphere_shell(6)));
    models.push_back(random_model(12, 0.3f, 17, {-3, 5, 2}));
    models.push_back(hollow_box(40));
    return models;
}

// A rotation: every third one a quarter turn about an axis (exact axis-aligned cases), the
// others random (unnormalised on purpose: poses normalise).
inline glm::quat test_rotation(rng& g, int i) {
    if (i % 3 == 0) {
        static const glm::quat quarter[] = {{0.70710678f, 0.70710678f, 0, 0}, {0.70710678f, 0, 0.70710678f, 0},
                                             {0.70710678f, 0, 0, 0.70710678f}, {1, 0, 0, 0}};
        return quarter[g.below(4)];
    }
    return {g.uniform(-2, 2), g.uniform(-2, 2), g.uniform(-2, 2), g.uniform(-2, 2) + 0.01f};
}

// `count` instances of the scene's models at random inside `bounds` widened by a quarter
// (so some stand partly outside the world), overlapping freely.
template <class World>
std::vector<instance_id> place_random(scene<World>& s, std::uint32_t models, const box3i& bounds, int count,
                                      std::uint64_t seed) {
    rng g(seed);
    glm::vec3 lo(bounds.min), hi(bounds.max), margin = (hi - lo) * 0.25f;
    std::vector<instance_id> ids;
    for (int i = 0; i < count; ++i) {
        pose p;
        for (int a = 0; a < 3; ++a) p.position[a] = g.uniform(lo[a] - margin[a], hi[a] + margin[a]);
        p.rotation = test_rotation(g, i);
        p.scale = i % 5 == 4 ? 0.5f + g.uniform() * 1.5f : 1.0f;
        ids.push_back(s.add(model_id(g.below(int(models))), p));
    }
    return ids;
}

// Rays over the world and every instance box: the check mix plus rays aimed at instances.
template <class World>
std::vector<ray> scene_rays(const scene<World>& s, const box3i& world, std::size_t count, std::uint64_t seed) {
    box3i all = world;
    for (std::size_t id = 0; id < s.slot_count(); ++id)
        if (auto st = s.instance(instance_id(id))) {
            world_box b = placed_box(st->where, s.model(st->model).extent());
            all.include(glm::ivec3(glm::floor(b.min)));
            all.include(glm::ivec3(glm::ceil(b.max)));
        }
    auto rays = check_rays(all, 2, count / 2, seed);
    rng g(seed + 1);
    for (std::size_t i = 0; i < count / 2 && s.slot_count() > 0; ++i) {  // at an instance's centre
        auto st = s.instance(instance_id(g.below(int(s.slot_count()))));
        if (!st) continue;
        ray r;
        r.origin = glm::vec3(all.min) - glm::vec3(5.0f) + glm::vec3(g.uniform(), g.uniform(), g.uniform()) * glm::vec3(all.extent() + 10);
        r.direction = glm::normalize(st->where.position + glm::vec3(g.uniform(-3, 3), g.uniform(-3, 3), g.uniform(-3, 3)) - r.origin);
        rays.push_back(r);
    }
    return rays;
}

struct scene_check {
    std::size_t rays = 0, entity_hits = 0, mismatches = 0;
    std::string first;
};

// The reference's closest hits for `rays`.
inline std::vector<hit> reference_hits(scene_reference& ref, std::span<const ray> rays) {
    std::vector<hit> want(rays.size());
    for (std::size_t i = 0; i < rays.size(); ++i) want[i] = ref.trace(rays[i], VX_MODE_CLOSEST);
    return want;
}

// Closest and any hits of the tracer against the reference's closest hits `want`: geometry,
// face, material and status for closest hits (steps are the structure's own), status for
// any hits.
template <class Tracer>
scene_check check_against(Tracer& t, std::span<const hit> want, std::span<const ray> rays) {
    scene_check c;
    c.rays = rays.size();
    std::vector<hit> got(rays.size()), any(rays.size());
    t.closest_hit(rays, got);
    t.any_hit(rays, any);
    for (std::size_t i = 0; i < rays.size(); ++i) {
        hit w = want[i], g = got[i];
        g.steps = w.steps = 0;
        if (hit_instance(w)) ++c.entity_hits;
        bool ok = same_bits(g, w) && any[i].status == w.status;
        if (!ok && c.mismatches++ == 0)
            c.first = describe(rays[i]) + "\n  got  " + describe(got[i]) + "\n  want " + describe(want[i]) +
                      "\n  any-hit status " + std::to_string(any[i].status);
    }
    return c;
}

template <class Tracer>
scene_check check_against(Tracer& t, scene_reference& ref, std::span<const ray> rays) {
    return check_against(t, std::span<const hit>(reference_hits(ref, rays)), rays);
}

}  // namespace voxray::test
