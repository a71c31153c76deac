// Cameras and primary rays.
//
//   voxray::camera cam = voxray::look_at({-40, 60, -40}, {32, 16, 32}, 50.0f);  // eye, target, fov
//   std::vector<voxray::ray> rays = voxray::primary_rays(cam, 1280, 720);      // row-major, top-left first
//   voxray::ray r = voxray::primary_ray(cam, x, y, 1280, 720);                  // one pixel
//   auto tiled = voxray::primary_rays(cam, 1280, 720, voxray::pixel_order::tiles);  // 8x8 tiles, Z order
//   // tiled[i] is the ray of pixel voxray::pixel_sequence(1280, 720, voxray::pixel_order::tiles)[i]
//
// Directions are normalized, so a hit's t is a distance in voxels. auto_camera frames a
// whole box (the views of `voxray render --view N`).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "voxray/core/box.hpp"
#include "voxray/core/ray.hpp"

namespace voxray {

// A pinhole camera: `position` (the eye) looks at `target`; `up` need not be exactly
// perpendicular to the view; fov_y_degrees is the vertical field of view.
struct camera {
    glm::vec3 position{0.0f};
    glm::vec3 target{0.0f, 0.0f, 1.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fov_y_degrees = 50.0f;
};

// A camera at `eye` looking at `target`; `up` is swapped for another axis when the view
// runs along it (looking straight up or down), where it could not orient the image.
inline camera look_at(glm::vec3 eye, glm::vec3 target, float fov_y_degrees = 50.0f, glm::vec3 up = {0.0f, 1.0f, 0.0f}) {
    camera c{eye, target, up, fov_y_degrees};
    glm::vec3 forward = target - eye;
    if (glm::length(forward) > 0.0f && glm::length(glm::cross(glm::normalize(forward), up)) < 1e-6f)
        c.up = glm::vec3(up.z, up.x, up.y);  // the next axis over
    return c;
}

// A view of the whole box from outside, looking down at about 30 degrees. `view` picks
// the azimuth (0: the default three-quarter view; others orbit in 8 steps); `up_axis` is
// 1 for Y-up and 2 for Z-up scenes (voxel_model::up_axis).
inline camera auto_camera(const box3i& bounds, int up_axis, int view = 0) {
    glm::vec3 lo(bounds.min), hi(bounds.max);
    glm::vec3 centre = (lo + hi) * 0.5f;
    float radius = 0.5f * glm::length(hi - lo) + 1.0f;
    float azimuth = 0.7853982f * float(view) + 0.6f;  // 45 degrees a view
    float elevation = 0.52f;
    glm::vec3 up(0.0f), a(0.0f), b(0.0f);
    up[up_axis] = 1.0f;
    a[(up_axis + 1) % 3] = 1.0f;
    b[(up_axis + 2) % 3] = 1.0f;
    glm::vec3 dir = std::cos(elevation) * (std::cos(azimuth) * a + std::sin(azimuth) * b) + std::sin(elevation) * up;
    camera c;
    c.fov_y_degrees = 50.0f;
    float distance = radius / std::sin(0.5f * c.fov_y_degrees * 0.01745329f) * 0.7f;
    c.position = centre + dir * distance;
    c.target = centre;
    c.up = up;
    return c;
}

// The camera's frame, computed once for many pixels.
struct camera_frame {
    glm::vec3 origin, forward, right, up;
    float half_w, half_h;
    int width, height;

    camera_frame(const camera& c, int width_px, int height_px) : origin(c.position), width(width_px), height(height_px) {
        forward = glm::normalize(c.target - c.position);
        right = glm::normalize(glm::cross(forward, c.up));
        up = glm::cross(right, forward);
        half_h = std::tan(0.5f * c.fov_y_degrees * 0.01745329f);
        half_w = half_h * float(width) / float(height);
    }

    // The ray through pixel (x, y)'s centre; (0, 0) is the top-left pixel.
    ray pixel(int x, int y) const { return through(float(x) + 0.5f, float(y) + 0.5f); }

    // The ray through point (px, py) of the picture, in pixels from its top-left corner
    // (several rays a pixel).
    ray through(float px, float py) const {
        float u = (px / float(width) * 2.0f - 1.0f) * half_w;
        float v = (1.0f - py / float(height) * 2.0f) * half_h;
        ray r;
        r.origin = origin;
        r.direction = glm::normalize(forward + u * right + v * up);
        return r;
    }
};

inline ray primary_ray(const camera& c, int x, int y, int width, int height) {
    return camera_frame(c, width, height).pixel(x, y);
}

// The order of a picture's rays. `rows`: row-major from the top-left. `tiles`: 8x8 tiles,
// row-major, and each tile's pixels in Morton (Z) order, so that the rays a SIMD lane group
// walks together look at neighbouring cells (tiles at the right and bottom edges keep only
// their pixels inside the picture).
enum class pixel_order { rows, tiles };
inline constexpr int pixel_tile = 8;

// Every pixel once, in `order`.
inline std::vector<glm::ivec2> pixel_sequence(int width, int height, pixel_order order) {
    std::vector<glm::ivec2> pixels;
    pixels.reserve(std::size_t(std::max(width, 0)) * std::size_t(std::max(height, 0)));
    if (order == pixel_order::rows) {
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) pixels.push_back({x, y});
        return pixels;
    }
    for (int ty = 0; ty < height; ty += pixel_tile)
        for (int tx = 0; tx < width; tx += pixel_tile)
            for (std::uint32_t i = 0; i < pixel_tile * pixel_tile; ++i) {
                // Z order: x from the even bits of i, y from the odd ones.
                glm::ivec2 p(tx, ty);
                for (int bit = 0; (1 << bit) < pixel_tile; ++bit)
                    p += glm::ivec2(int(i >> (2 * bit) & 1u), int(i >> (2 * bit + 1) & 1u)) << bit;
                if (p.x < width && p.y < height) pixels.push_back(p);
            }
    return pixels;
}

// One ray per pixel through the pixel centre, in `order` (row-major from the top-left by
// default; pixel_sequence says which pixel each ray is).
inline std::vector<ray> primary_rays(const camera& c, int width, int height, pixel_order order = pixel_order::rows) {
    camera_frame frame(c, width, height);
    const std::vector<glm::ivec2> pixels = pixel_sequence(width, height, order);
    std::vector<ray> rays;
    rays.reserve(pixels.size());
    for (glm::ivec2 p : pixels) rays.push_back(frame.pixel(p.x, p.y));
    return rays;
}

}  // namespace voxray
