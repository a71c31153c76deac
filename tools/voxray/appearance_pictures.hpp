// What the appearance benchmarks (appearance-bench, appearance-world-bench) share: the rays a
// method's picture is walked with (4 a pixel, at the centres of its 2 x 2 strata), the walked
// rays blended into a picture, the lights, and the comparison with a reference in sRGB: MSE
// (all pixels, and the pixels the reference covers), PSNR and SSIM (scikit-image's
// parameters, per channel; scripts/appearance_table.py checks them with scikit-image itself).
#pragma once
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/geometric.hpp>

#include "appearance_reference.hpp"
#include "image_writer.hpp"
#include "ssim.hpp"
#include "voxray/appearance/pixel.hpp"
#include "voxray/io/surface_sample.hpp"
#include "voxray/rays/camera.hpp"

namespace voxray::tool {

inline std::vector<std::uint8_t> srgb8(const linear_picture& p) {
    std::vector<std::uint8_t> out;
    out.reserve(p.rgb.size() * 3);
    for (glm::vec3 c : p.rgb) {
        rgba e = io::encode_srgb8(glm::vec4(glm::clamp(c, 0.0f, 1.0f), 1.0f));
        out.insert(out.end(), {e.r, e.g, e.b});
    }
    return out;
}

struct picture_errors {
    double mse = 0, mse_foreground = 0, psnr = 0, ssim = 0;
};

// `got` against `ref` (sRGB, 3 bytes a pixel); the foreground: where `coverage` > 0.
inline picture_errors compare(const std::vector<std::uint8_t>& ref, const std::vector<std::uint8_t>& got,
                              const std::vector<float>& coverage, int w, int h) {
    picture_errors e;
    double all = 0, fg = 0;
    std::size_t fg_pixels = 0;
    for (std::size_t i = 0; i < coverage.size(); ++i) {
        double sq = 0;
        for (int c = 0; c < 3; ++c) {
            double d = (double(ref[3 * i + c]) - double(got[3 * i + c])) / 255.0;
            sq += d * d;
        }
        all += sq;
        if (coverage[i] > 0) fg += sq, ++fg_pixels;
    }
    e.mse = all / double(3 * coverage.size());
    e.mse_foreground = fg_pixels ? fg / double(3 * fg_pixels) : 0.0;
    e.psnr = e.mse > 0 ? 10.0 * std::log10(1.0 / e.mse) : 99.0;
    e.ssim = ssim_rgb8_channels(ref, got, w, h);
    return e;
}

// The light in front (from behind the camera, above) or behind the model (facing it).
inline glm::vec3 light_direction(const camera& cam, bool front) {
    glm::vec3 to_eye = glm::normalize(cam.position - cam.target);
    glm::vec3 horizontal = to_eye - glm::dot(to_eye, cam.up) * cam.up;
    if (glm::length(horizontal) < 1e-4f) horizontal = glm::vec3(1, 0, 0);
    horizontal = glm::normalize(horizontal);
    return glm::normalize((front ? horizontal : -horizontal) + 0.8f * cam.up);
}

// 4 rays a pixel, pixel by pixel, at the centres of its 2 x 2 strata.
inline std::vector<ray> four_rays_a_pixel(const camera& cam, int width, int height) {
    camera_frame frame(cam, width, height);
    std::vector<ray> rays;
    rays.reserve(std::size_t(width) * std::size_t(height) * 4);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            for (int s = 0; s < 4; ++s)
                rays.push_back(
                    frame.through(float(x) + 0.25f + 0.5f * float(s & 1), float(y) + 0.25f + 0.5f * float(s >> 1)));
    return rays;
}

// The walked four_rays_a_pixel, each over the background, averaged a pixel.
inline linear_picture blend_four(const std::vector<appearance_pixel>& px, int width, int height, glm::vec3 background) {
    const std::size_t pixels = std::size_t(width) * std::size_t(height);
    linear_picture p{width, height, std::vector<glm::vec3>(pixels, glm::vec3(0.0f)), {}};
    for (std::size_t i = 0; i < px.size(); ++i)
        p.rgb[i / 4] += 0.25f * (glm::vec3(px[i].r, px[i].g, px[i].b) + px[i].transmittance * background);
    return p;
}

// Pictures of one size side by side, as one PNG.
inline void write_strip(const std::vector<std::vector<std::uint8_t>>& parts, int width, int height,
                        const std::string& path) {
    std::vector<std::uint8_t> joined;
    for (int y = 0; y < height; ++y)
        for (const auto& part : parts)
            joined.insert(joined.end(), part.begin() + std::ptrdiff_t(3 * std::size_t(y) * std::size_t(width)),
                          part.begin() + std::ptrdiff_t(3 * std::size_t(y + 1) * std::size_t(width)));
    write_image(path, width * int(parts.size()), height, joined);
}

}  // namespace voxray::tool
