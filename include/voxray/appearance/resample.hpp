// Coarser appearance tables made from the level below (issue 25, item 6). A coarse voxel's
// sampling and opacity rays meet no triangles here: they are walked through the finer
// level and its table with the compositing walk (appearance/walk.inc, on the CPU's scalar
// lanes), and the records are fitted to what the walk saw, by the same code as a table
// made from triangles (precompute.hpp's build_table). So every level of a chain is built
// from the one below, and models without triangles (.vox scenes, world chunks) get coarse
// tables too.
//
// Voxel c of the coarse level covers voxels [2c, 2c + 2) of the finer one. A walked segment
// gives the colour and normal blended along it and its coverage, 1 - transmittance:
//   - an opacity ray counts with its coverage (opacity_rays.hpp);
//   - a sampling ray, which the record fits take as stopped or passed, stops where its
//     coverage exceeds a uniform number hashed from the ray and the seed: it stops with
//     probability coverage, and the table is the same for a seed and any thread count.
// A segment whose blended normal turns away from the ray met the finer surface from behind:
// it occludes without a sample, as a one-sided triangle does. The walk runs unlit (ambient
// 1), so the colours are the finer records' own; a six directions table is lit when made and
// cannot be a finer level.
#pragma once
#include <algorithm>
#include <bit>
#include <cstdint>
#include <tuple>
#include <utility>
#include <vector>

#include <glm/geometric.hpp>

#include "voxray/appearance/pixel.hpp"
#include "voxray/appearance/precompute.hpp"
#include "voxray/appearance/walk_inputs.hpp"
#include "voxray/core/error.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::appearance {

// The coarse voxels over `finer`: one wherever any of its 8 children is set (a voxel
// partly covered is still seen), of the children's most frequent material (the smallest
// among equals).
inline voxel_model coarser_voxels(const voxel_model& finer) {
    std::vector<std::tuple<int, int, int, std::uint8_t>> children;
    finer.for_each_voxel([&](glm::ivec3 p, std::uint8_t m) { children.emplace_back(p.z >> 1, p.y >> 1, p.x >> 1, m); });
    std::sort(children.begin(), children.end());
    voxel_model coarse;
    for (std::size_t a = 0; a < children.size();) {
        auto same_parent = [&](std::size_t i) {
            return std::get<0>(children[i]) == std::get<0>(children[a]) &&
                   std::get<1>(children[i]) == std::get<1>(children[a]) &&
                   std::get<2>(children[i]) == std::get<2>(children[a]);
        };
        std::size_t b = a, best = 0;
        std::uint8_t material = std::get<3>(children[a]);
        while (b < children.size() && same_parent(b)) {  // sorted: equal materials are adjacent
            std::size_t run = b;
            while (run < children.size() && same_parent(run) && std::get<3>(children[run]) == std::get<3>(children[b]))
                ++run;
            if (run - b > best) best = run - b, material = std::get<3>(children[b]);
            b = run;
        }
        coarse.set({std::get<2>(children[a]), std::get<1>(children[a]), std::get<0>(children[a])}, material);
        a = b;
    }
    return coarse;
}

// The surfaces a coarse level's rays meet: the finer level, walked. `Walker` is a CPU
// appearance_walker of the finer structure and table (cpu/appearance_walk.hpp).
template <class Walker>
struct finer_level_surfaces {
    const Walker& finer;
    std::uint64_t seed = 1;

    float coverage(glm::dvec3 origin, glm::dvec3 direction, double length) const {
        return first_surface(origin, direction, length).coverage;
    }

    segment_hit first_surface(glm::dvec3 origin, glm::dvec3 direction, double length) const {
        // In the finer level's voxels, a hair inside the coarse voxel at both ends: a ray
        // that starts on a voxel's side must not be taken for one in the neighbour behind it.
        constexpr float inset = 1e-4f;
        ray r;
        r.origin = glm::vec3(origin * 2.0), r.direction = glm::vec3(direction);
        r.tmin = inset, r.tmax = std::max(float(length * 2.0) - inset, inset);
        appearance_pixel p = finer.walk_one(r, {.to_light = {0.0f, 1.0f, 0.0f}, .ambient = 1.0f, .shadows = false});
        segment_hit h;
        h.coverage = std::clamp(1.0f - p.transmittance, 0.0f, 1.0f);
        h.hit = h.coverage > stop_threshold(r);
        if (!h.hit) return h;
        h.t = std::max(p.t, 0.0f) * 0.5f;
        glm::vec3 n(p.nx, p.ny, p.nz);
        float length_n = glm::length(n);
        h.seen.normal = length_n > 0.0f ? n / length_n : -r.direction;
        // Surfaces seen from behind occlude without a sample, as a one-sided triangle does.
        h.sample = glm::dot(h.seen.normal, r.direction) <= 0.0f;
        glm::vec3 colour = glm::clamp(glm::vec3(p.r, p.g, p.b) / h.coverage, 0.0f, 1.0f);
        h.seen.colour = glm::vec4(colour, 1.0f);
        return h;
    }

private:
    // Uniform in [0, 1), from the ray's bits and the seed.
    float stop_threshold(const ray& r) const {
        std::uint64_t key = seed;
        for (float v : {r.origin.x, r.origin.y, r.origin.z, r.direction.x, r.direction.y, r.direction.z, r.tmax})
            key = mix64(key ^ std::bit_cast<std::uint32_t>(v));
        return float(double(key >> 11) * 0x1.0p-53);
    }
};

// The table of the coarse `voxels` (any order; each covers voxels [2c, 2c + 2) of the finer
// level that `finer` walks), of kind o.kind, re-sampled from the finer level. The table is
// the same for any o.threads.
template <class Walker>
appearance_table resample(const Walker& finer, std::vector<glm::ivec3> voxels, const precompute_options& o = {},
                          precompute_stats* stats = nullptr) {
    if (finer.kind() == VX_APP_KIND_SIX)
        fail("appearance resample: the finer level's table is a six directions one, whose colours are lit when "
             "made; re-sample from averages, sggx, compact or faithful records");
    return build_table(finer_level_surfaces<Walker>{finer, o.sampling.seed}, std::move(voxels), o, stats);
}

// The same for the voxels of `coarse` (coarser_voxels, or the coarse structure's own).
template <class Walker>
appearance_table resample(const Walker& finer, const voxel_model& coarse, const precompute_options& o = {},
                          precompute_stats* stats = nullptr) {
    std::vector<glm::ivec3> voxels;
    coarse.for_each_voxel([&](glm::ivec3 p, std::uint8_t) { voxels.push_back(p); });
    return resample(finer, std::move(voxels), o, stats);
}

}  // namespace voxray::appearance
