// A pinhole camera and the automatic views used by `voxray render`, `check` and `bench`.
#pragma once
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "voxray/core/box.hpp"
#include "voxray/core/ray.hpp"

namespace voxray {

struct camera {
    glm::vec3 position{0.0f};
    glm::vec3 target{0.0f, 0.0f, 1.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fov_y_degrees = 50.0f;
};

// A view of the whole box from outside, looking down at about 30 degrees. `view` picks
// the azimuth (0: the default three-quarter view; others orbit in 8 steps); `up_axis` is
// 1 for Y-up and 2 for Z-up scenes.
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

// One ray per pixel through the pixel centre, row-major from the top-left. Directions are
// normalized, so t is a distance.
inline std::vector<ray> primary_rays(const camera& c, int width, int height) {
    glm::vec3 forward = glm::normalize(c.target - c.position);
    glm::vec3 right = glm::normalize(glm::cross(forward, c.up));
    glm::vec3 up = glm::cross(right, forward);
    float half_h = std::tan(0.5f * c.fov_y_degrees * 0.01745329f);
    float half_w = half_h * float(width) / float(height);
    std::vector<ray> rays(std::size_t(width) * height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            float u = ((float(x) + 0.5f) / float(width) * 2.0f - 1.0f) * half_w;
            float v = (1.0f - (float(y) + 0.5f) / float(height) * 2.0f) * half_h;
            ray& r = rays[std::size_t(y) * width + x];
            r.origin = c.position;
            r.direction = glm::normalize(forward + u * right + v * up);
        }
    return rays;
}

}  // namespace voxray
