// Solid fill of a surface-voxelized mesh by ray parity, using Embree.
//
// For every voxel column along one axis a ray runs through the voxel centres;
// the mesh surfaces it crosses are collected in order (rtcIntersect1 again and
// again, each time starting just past the last hit), and the voxels whose
// centres lie between crossing 2i and 2i+1 are inside:
//
//   ray  ->   |####|      |######|        crossings c0 c1   c2 c3
//   voxels    .IIII.      .IIIIII.        I: centre in [c0,c1] or [c2,c3]
//
// The result is right for closed (watertight) meshes. Open meshes such as
// sponza give streaks; a column with an odd number of crossings drops its last
// one (so it leaks as little as possible). Hits closer together than 1e-4 voxel
// (or 4 float ulps far from the origin) count once: a ray through a shared edge or vertex reports it from both
// triangles, and Embree's robust mode guarantees at least one of them.
//
// Only empty voxels are filled, so the surface keeps its colours. The model
// must come from io::voxelize with the same mesh and resolution.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include <embree3/rtcore.h>

#include "voxray/core/error.hpp"
#include "voxray/embree/device.hpp"
#include "voxray/embree/triangle_scene.hpp"
#include "voxray/io/mesh.hpp"
#include "voxray/io/voxelizer.hpp"
#include "voxray/model/build_threads.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::embree {

struct fill_options {
    int axis = 2;            // rays run along x (0), y (1) or z (2)
    std::uint8_t value = 0;  // palette index of filled voxels; 0: that of the first
                             // surface voxel at or after the span's entry point
    unsigned threads = 0;    // 0: std::thread::hardware_concurrency()
};

// Fills the interior; returns the number of voxels added.
inline std::uint64_t fill_interior(voxel_model& model, const io::triangle_mesh& mesh, int resolution,
                                   const fill_options& opt = {}) {
    if (opt.axis < 0 || opt.axis > 2) fail("fill_interior: axis ", opt.axis, " is not 0, 1 or 2");
    if (mesh.triangles.empty()) fail("fill_interior: the mesh has no triangles");
    mesh.validate();
    auto grid = io::make_grid_map(mesh.bounds(), resolution);

    // The scene lives in voxel space, so rays and spans need no conversion.
    triangle_scene scene(mesh, grid);

    const int w = opt.axis, u = (w + 1) % 3, v = (w + 2) % 3;
    const int nu = grid.dims[u], nv = grid.dims[v], nw = grid.dims[w];
    struct span {
        int cu, cv, first, last;  // inclusive voxel range along w
    };
    unsigned threads = resolve_build_threads(opt.threads, std::size_t(nv));
    std::vector<std::vector<span>> spans(threads);
    run_build_threads(threads, [&](unsigned id) {
        RTCIntersectContext ctx;
        std::vector<float> hits;
        for (int cv = int(id); cv < nv; cv += int(threads))
            for (int cu = 0; cu < nu; ++cu) {
                hits.clear();
                float tnear = 0.0f;
                for (;;) {
                    RTCRayHit rh{};
                    float org[3];
                    org[u] = float(cu) + 0.5f, org[v] = float(cv) + 0.5f, org[w] = -1.0f;
                    rh.ray.org_x = org[0], rh.ray.org_y = org[1], rh.ray.org_z = org[2];
                    float dir[3] = {0, 0, 0};
                    dir[w] = 1.0f;
                    rh.ray.dir_x = dir[0], rh.ray.dir_y = dir[1], rh.ray.dir_z = dir[2];
                    rh.ray.tnear = tnear;
                    rh.ray.tfar = float(nw) + 2.0f;
                    rh.ray.mask = ~0u;
                    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                    rtcInitIntersectContext(&ctx);
                    rtcIntersect1(scene.handle(), &ctx, &rh);
                    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) break;
                    hits.push_back(rh.ray.tfar - 1.0f);  // w coordinate of the crossing
                    // Past this hit by more than float rounding at this distance.
                    tnear = rh.ray.tfar + std::max(1e-4f, rh.ray.tfar * 0x1.0p-18f);
                    // Each triangle is crossed at most once, so more hits mean a bug.
                    if (hits.size() > mesh.triangles.size())
                        fail("fill_interior: column (", cu, ", ", cv, ") reports more crossings than triangles");
                }
                for (std::size_t i = 0; i + 1 < hits.size(); i += 2) {
                    // Voxel k's centre k + 0.5 within [hits[i], hits[i+1]].
                    double f = std::ceil(double(hits[i]) - 0.5), l = std::floor(double(hits[i + 1]) - 0.5);
                    f = std::max(f, 0.0), l = std::min(l, double(nw - 1));
                    if (f <= l) spans[id].push_back({cu, cv, int(f), int(l)});
                }
            }
    });

    std::uint64_t added = 0;
    for (auto& list : spans)
        for (auto& s : list) {
            glm::ivec3 p;
            p[u] = s.cu, p[v] = s.cv;
            std::uint8_t value = opt.value;
            if (!value) {  // colour of the surface where the span starts
                for (p[w] = std::max(0, s.first - 1); p[w] <= s.last && !value; ++p[w]) value = model.get(p);
                if (!value) value = 1;
            }
            for (p[w] = s.first; p[w] <= s.last; ++p[w])
                if (!model.get(p)) {
                    model.set(p, value);
                    ++added;
                }
        }
    return added;
}

}  // namespace voxray::embree
