// The codes records store (layout.h), on the host: colours as the 8-bit code whose value
// under the kernels' sRGB cubic is nearest, unit normals octahedral in signed n-bit parts,
// 0..1 values in n levels.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "voxray/appearance/layout.h"

namespace voxray::appearance {

inline double srgb_cubic(std::uint32_t code) {
    float x = float(code) * (1.0f / 255.0f);
    return double(VX_APP_SRGB_CUBIC(x));
}

// The code whose decoded value is nearest to linear value x (the cubic rises on 0..1).
inline std::uint32_t srgb_code(double x) {
    if (!(x > 0.0)) return 0;  // NaN too
    std::uint32_t lo = 0, hi = 255;
    while (hi - lo > 1) {
        std::uint32_t mid = (lo + hi) / 2;
        (srgb_cubic(mid) < x ? lo : hi) = mid;
    }
    return x - srgb_cubic(lo) <= srgb_cubic(hi) - x ? lo : hi;
}

// Octahedral mapping of a unit vector to [-1, 1]^2 and back.
inline glm::vec2 octahedral(glm::vec3 n) {
    n /= std::fabs(n.x) + std::fabs(n.y) + std::fabs(n.z);
    if (n.z >= 0) return {n.x, n.y};
    return {(1.0f - std::fabs(n.y)) * (n.x >= 0 ? 1.0f : -1.0f), (1.0f - std::fabs(n.x)) * (n.y >= 0 ? 1.0f : -1.0f)};
}
inline glm::vec3 from_octahedral(glm::vec2 e) {
    glm::vec3 n(e.x, e.y, 1.0f - std::fabs(e.x) - std::fabs(e.y));
    if (n.z < 0) {
        float x = n.x;
        n.x = (1.0f - std::fabs(n.y)) * (x >= 0 ? 1.0f : -1.0f);
        n.y = (1.0f - std::fabs(x)) * (n.y >= 0 ? 1.0f : -1.0f);
    }
    return glm::normalize(n);
}

// x in -1..1 as a signed `bits`-bit integer (two's complement, in the low bits) and back.
inline std::uint32_t snorm(float x, unsigned bits) {
    int scale = (1 << (bits - 1)) - 1;
    int v = int(std::lround(std::clamp(std::isnan(x) ? 0.0f : x, -1.0f, 1.0f) * float(scale)));  // NaN: 0
    return std::uint32_t(v) & ((1u << bits) - 1u);
}
inline float from_snorm(std::uint32_t v, unsigned bits) {
    std::uint32_t sign = 1u << (bits - 1);
    int x = int(v & ((sign << 1) - 1u)) - int((v & sign) << 1);
    return std::max(float(x) / float(sign - 1u), -1.0f);
}

// 0..1 in `levels` + 1 codes.
inline std::uint32_t unorm(double x, std::uint32_t levels) {
    return std::uint32_t(std::lround(std::clamp(std::isnan(x) ? 0.0 : x, 0.0, 1.0) * double(levels)));
}

}  // namespace voxray::appearance
