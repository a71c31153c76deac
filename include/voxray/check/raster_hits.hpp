// A raster frame's pixels (voxel and face, meshing/raster_pixel.hpp) against the ray
// tracer's primary hits through the same pixels' centres. The two agree except where a
// voxel edge passes (within rounding) through a pixel's centre, so a pixel may differ only
// on an edge of the ray-traced picture: where one of its four neighbours shows another
// voxel or face, or nothing.
#pragma once
#include <cstddef>
#include <cstdint>
#include <span>

#include "voxray/core/hit.hpp"
#include "voxray/meshing/raster_pixel.hpp"

namespace voxray::check {

struct raster_agreement {
    std::uint64_t covered = 0;    // pixels where either side shows a voxel
    std::uint64_t equal = 0;      // of those, the same voxel and face on both
    std::uint64_t off_edges = 0;  // differing pixels that are not on an edge

    // Differing pixels beyond `share` of the covered ones (the 99.5 %).
    std::uint64_t beyond(double share) const {
        double allowed = (1.0 - share) * double(covered);
        double differing = double(covered - equal);
        return differing > allowed ? std::uint64_t(differing - allowed + 0.999) : 0;
    }
};

inline bool same_surface(const raster_pixel& p, const hit& h) {
    if (!h.is_hit()) return p.face == VX_FACE_NONE;
    return p.face == std::uint32_t(h.normal) && p.voxel == h.voxel;
}

inline bool same_surface(const hit& a, const hit& b) {
    return a.is_hit() == b.is_hit() && (!a.is_hit() || (a.voxel == b.voxel && a.normal == b.normal));
}

// Both row-major, width x height, top row first.
inline raster_agreement compare_raster_hits(std::span<const raster_pixel> pixels, std::span<const hit> hits, int width,
                                            int height) {
    raster_agreement a;
    auto at = [&](int x, int y) { return std::size_t(y) * std::size_t(width) + std::size_t(x); };
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            std::size_t i = at(x, y);
            if (pixels[i].face == VX_FACE_NONE && !hits[i].is_hit()) continue;
            ++a.covered;
            if (same_surface(pixels[i], hits[i])) {
                ++a.equal;
                continue;
            }
            const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
            bool edge = false;
            for (int k = 0; k < 4; ++k) {
                int nx = x + dx[k], ny = y + dy[k];
                if (nx >= 0 && ny >= 0 && nx < width && ny < height)
                    edge = edge || !same_surface(hits[at(nx, ny)], hits[i]);
            }
            a.off_edges += !edge;
        }
    return a;
}

}  // namespace voxray::check
