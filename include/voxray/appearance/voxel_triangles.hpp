// The triangles one voxel's sampling rays can meet, and a segment's first hit among them.
//
// Why: every sampling and opacity ray of a voxel runs inside that voxel (widened by
// first_surface's margin), so only the few triangles that reach the widened cube can stop
// it. Gathering them once a voxel (Embree's point query over the scene's own BVH, then the
// exact box test) and testing each ray against that short list costs a fraction of a BVH
// descent from the root for each of a voxel's ~260 rays. A voxel that many triangles reach
// keeps tracing the whole scene (gather() says so): the list's cost grows with its length.
//
// The hits are the scene's: the same corners (voxel space, as Embree holds them), the same
// barycentric convention and the same geometric normal; only the arithmetic differs, in
// floats about the voxel's corner, where the numbers are small (so finer than Embree's in
// voxel space); tests/appearance/test_voxel_triangles.cpp checks them against Embree's.
#pragma once
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "voxray/io/triangle_box.hpp"

namespace voxray::appearance {

// What first_hit returns, as the Embree scene's hit: t along the ray, the triangle, the
// weights of its corners and its unit geometric normal, wound as the triangle.
struct local_hit {
    float t = 0;
    std::uint32_t triangle = 0;
    glm::dvec3 barycentric{1, 0, 0};
    glm::vec3 normal{0, 0, 1};
};

class voxel_triangles {
public:
    // How far outside its cube a voxel's rays may reach (first_surface's margin, 1e-4, with room).
    static constexpr double reach = 4e-4;
    // Past this many triangles a list is slower than the scene's BVH.
    static constexpr std::size_t max_triangles = 64;

    // The triangles of `scene` that meet voxel `voxel`'s cube widened by `reach`; false when
    // there are over max_triangles of them (then trace the scene itself).
    template <class Scene>
    bool gather(const Scene& scene, glm::ivec3 voxel) {
        corner_ = glm::dvec3(voxel);
        candidates_.clear();
        blocks_.clear();
        normals_.clear();
        ids_.clear();
        const glm::dvec3 centre = corner_ + 0.5;
        scene.triangles_near(glm::vec3(centre), float(0.8660254037844386 + 2.0 * reach), candidates_);
        for (std::uint32_t id : candidates_) {
            std::array<glm::vec3, 3> c = scene.corners(id);
            glm::dvec3 a = glm::dvec3(c[0]) - corner_, b = glm::dvec3(c[1]) - corner_, d = glm::dvec3(c[2]) - corner_;
            if (!io::triangle_box_overlap(glm::dvec3(0.5), glm::dvec3(0.5 + reach), a, b, d)) continue;
            if (ids_.size() == max_triangles) return false;
            add(a, b - a, d - a, id);
        }
        return true;
    }

    std::size_t size() const { return ids_.size(); }

    // The closest hit of org + t dir with t in [tnear, tfar] (voxel space), as the scene's
    // first_hit: Moller-Trumbore about the voxel's corner, on eight triangles at once (GCC's
    // and Clang's vector types, as the CPU backend's lanes), then the nearest of them.
    std::optional<local_hit> first_hit(glm::vec3 org, glm::vec3 dir, float tnear, float tfar) const {
        const glm::vec3 o = glm::vec3(glm::dvec3(org) - corner_);
        float best = tfar, best_u = 0, best_v = 0;
        std::size_t found = ids_.size();
        for (std::size_t first = 0; first < ids_.size(); first += lanes) {
            const block& b = blocks_[first / lanes];
            // p = dir x ac, det = ab . p, s = o - a, q = s x ab
            floats px = dir.y * b.ac[2] - dir.z * b.ac[1];
            floats py = dir.z * b.ac[0] - dir.x * b.ac[2];
            floats pz = dir.x * b.ac[1] - dir.y * b.ac[0];
            floats det = b.ab[0] * px + b.ab[1] * py + b.ab[2] * pz;
            ints flat = det == 0.0f;  // parallel to the plane, or degenerate (a block's empty lanes)
            floats inv = 1.0f / (flat ? floats{} + 1.0f : det);
            floats sx = o.x - b.a[0], sy = o.y - b.a[1], sz = o.z - b.a[2];
            floats qx = sy * b.ab[2] - sz * b.ab[1];
            floats qy = sz * b.ab[0] - sx * b.ab[2];
            floats qz = sx * b.ab[1] - sy * b.ab[0];
            floats u = (sx * px + sy * py + sz * pz) * inv;
            floats v = (dir.x * qx + dir.y * qy + dir.z * qz) * inv;
            floats t = (b.ac[0] * qx + b.ac[1] * qy + b.ac[2] * qz) * inv;
            ints inside = ~flat & (u >= 0.0f) & (v >= 0.0f) & (u + v <= 1.0f) & (t >= tnear) & (t <= best);
            // The lanes hit, in lane order (a block's empty lanes are flat): a mask's set bits,
            // not a branch a lane, whose outcome is as random as the rays.
            unsigned hits = 0;
            for (std::size_t i = 0; i < lanes; ++i) hits |= unsigned(inside[i] & 1) << i;
            for (; hits != 0; hits &= hits - 1) {
                const int i = std::countr_zero(hits);
                if (t[i] <= best) best = t[i], best_u = u[i], best_v = v[i], found = first + std::size_t(i);
            }
        }
        if (found == ids_.size()) return std::nullopt;
        return local_hit{best, ids_[found], {1.0 - double(best_u) - double(best_v), double(best_u), double(best_v)},
                         normals_[found]};
    }

private:
    static constexpr std::size_t lanes = 8;
    typedef float floats __attribute__((vector_size(4 * lanes)));
    typedef std::int32_t ints __attribute__((vector_size(4 * lanes)));
    struct block {  // eight triangles, one vector a coordinate (about the voxel's corner); unused lanes 0
        floats a[3], ab[3], ac[3];
    };
    void add(glm::dvec3 a, glm::dvec3 ab, glm::dvec3 ac, std::uint32_t id) {
        if (ids_.size() % lanes == 0) blocks_.push_back({});
        block& b = blocks_.back();
        std::size_t i = ids_.size() % lanes;
        for (int k = 0; k < 3; ++k) b.a[k][i] = float(a[k]), b.ab[k][i] = float(ab[k]), b.ac[k][i] = float(ac[k]);
        glm::dvec3 n = glm::cross(ab, ac);
        double length = glm::length(n);
        normals_.push_back(length > 0 ? glm::vec3(n / length) : glm::vec3(0, 0, 1));
        ids_.push_back(id);
    }

    glm::dvec3 corner_{0.0};
    std::vector<std::uint32_t> candidates_;
    std::vector<block> blocks_;
    std::vector<glm::vec3> normals_;
    std::vector<std::uint32_t> ids_;
};

}  // namespace voxray::appearance
