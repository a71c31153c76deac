// The structural similarity of two pictures (Wang et al. 2004), with the parameters
// scikit-image takes for Wang's (gaussian_weights, sigma 1.5, use_sample_covariance off): an
// 11 x 11 Gaussian window, C1 = (0.01 L)^2, C2 = (0.03 L)^2 with L = 255, averaged over the
// pixels whose window lies inside the picture. 1 for equal pictures.
//   ssim_rgb8           on luminance (Rec. 601 weights), for the world's frames;
//   ssim_rgb8_channels  each channel apart, then their mean: scikit-image's channel_axis.
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "voxray/core/error.hpp"

namespace voxray::tool {

// SSIM of two planes of width x height values in 0..255.
inline double ssim_plane(const std::vector<double>& x, const std::vector<double>& y, int width, int height) {
    const std::size_t n = std::size_t(width) * std::size_t(height);
    constexpr int radius = 5;
    if (width <= 2 * radius || height <= 2 * radius)
        fail("ssim: a ", width, " x ", height, " picture is smaller than the 11 x 11 window");
    double weight[2 * radius + 1], sum = 0;
    for (int k = -radius; k <= radius; ++k) sum += weight[k + radius] = std::exp(-double(k * k) / (2.0 * 1.5 * 1.5));
    for (double& w : weight) w /= sum;
    // Separable blur of one product image, rows then columns.
    auto blur = [&](auto&& value) {
        std::vector<double> rows(n), out(n);
        for (int r = 0; r < height; ++r)
            for (int c = radius; c < width - radius; ++c) {
                double s = 0;
                for (int k = -radius; k <= radius; ++k)
                    s += weight[k + radius] * value(std::size_t(r) * width + std::size_t(c + k));
                rows[std::size_t(r) * width + std::size_t(c)] = s;
            }
        for (int r = radius; r < height - radius; ++r)
            for (int c = radius; c < width - radius; ++c) {
                double s = 0;
                for (int k = -radius; k <= radius; ++k)
                    s += weight[k + radius] * rows[std::size_t(r + k) * width + std::size_t(c)];
                out[std::size_t(r) * width + std::size_t(c)] = s;
            }
        return out;
    };
    auto mx = blur([&](std::size_t i) { return x[i]; }), my = blur([&](std::size_t i) { return y[i]; });
    auto xx = blur([&](std::size_t i) { return x[i] * x[i]; }), yy = blur([&](std::size_t i) { return y[i] * y[i]; });
    auto xy = blur([&](std::size_t i) { return x[i] * y[i]; });
    const double c1 = (0.01 * 255) * (0.01 * 255), c2 = (0.03 * 255) * (0.03 * 255);
    double total = 0;
    std::size_t count = 0;
    for (int r = radius; r < height - radius; ++r)
        for (int c = radius; c < width - radius; ++c) {
            std::size_t i = std::size_t(r) * width + std::size_t(c);
            double vx = xx[i] - mx[i] * mx[i], vy = yy[i] - my[i] * my[i], cov = xy[i] - mx[i] * my[i];
            double mean_term = (2 * mx[i] * my[i] + c1) / (mx[i] * mx[i] + my[i] * my[i] + c1);
            total += mean_term * (2 * cov + c2) / (vx + vy + c2);
            ++count;
        }
    return total / double(count);
}

inline void check_rgb8_pair(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, int width,
                            int height) {
    std::size_t n = std::size_t(width) * std::size_t(height);
    if (a.size() != 3 * n || b.size() != 3 * n)
        fail("ssim: pictures of ", a.size(), " and ", b.size(), " bytes for ", width, " x ", height);
}

inline double ssim_rgb8(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, int width, int height) {
    check_rgb8_pair(a, b, width, height);
    auto luminance = [&](const std::vector<std::uint8_t>& rgb) {
        std::vector<double> y(rgb.size() / 3);
        for (std::size_t i = 0; i < y.size(); ++i)
            y[i] = 0.299 * rgb[3 * i] + 0.587 * rgb[3 * i + 1] + 0.114 * rgb[3 * i + 2];
        return y;
    };
    return ssim_plane(luminance(a), luminance(b), width, height);
}

inline double ssim_rgb8_channels(const std::vector<std::uint8_t>& a, const std::vector<std::uint8_t>& b, int width,
                                 int height) {
    check_rgb8_pair(a, b, width, height);
    double total = 0;
    for (int c = 0; c < 3; ++c) {
        auto channel = [&](const std::vector<std::uint8_t>& rgb) {
            std::vector<double> v(rgb.size() / 3);
            for (std::size_t i = 0; i < v.size(); ++i) v[i] = rgb[3 * i + std::size_t(c)];
            return v;
        };
        total += ssim_plane(channel(a), channel(b), width, height);
    }
    return total / 3.0;
}

}  // namespace voxray::tool
