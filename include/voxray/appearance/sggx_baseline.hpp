// The *SGGX* record (appearance/layout.h): the baseline after Vicini et al. 2021, as the
// paper re-implemented it (fed only by what lies inside the voxel): the SGGX fit of the
// samples' normals (appearance/sggx.hpp), their mean colour, and a density and correlation
// gamma of the non-exponential transmittance, fitted to the share of the sampling rays that
// stopped, per axis direction (six bins, as six_directions.hpp splits them).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "voxray/appearance/layout.h"
#include "voxray/appearance/record_codes.hpp"
#include "voxray/appearance/sggx.hpp"
#include "voxray/appearance/six_directions.hpp"
#include "voxray/appearance/voxel_sampler.hpp"

namespace voxray::appearance {

// Vicini et al.'s transmittance: exponential for gamma 1, linear (fully correlated) for 0.
inline double non_exponential_transmittance(double tau, double gamma) {
    return gamma * std::exp(-tau) + (1.0 - gamma) * std::max(1.0 - 0.5 * tau, 0.0);
}

// The opacity the record gives along unit w, for S, rho and gamma (the kernels use the
// same model, record.h).
inline double sggx_opacity(const glm::dmat3& s, double rho, double gamma, glm::dvec3 w) {
    double projected = std::sqrt(std::max(glm::dot(w, s * w), 0.0));
    double chord = std::fabs(w.x) + std::fabs(w.y) + std::fabs(w.z);
    return 1.0 - non_exponential_transmittance(rho * projected / chord, gamma);
}

inline std::array<std::uint32_t, VX_APP_SGGX_WORDS> sggx_record(const voxel_samples& v) {
    std::vector<glm::dvec3> normals;
    glm::dvec3 colour(0.0);
    for (const surface_sample& s : v.seen) normals.push_back(glm::dvec3(s.normal)), colour += glm::dvec3(s.colour);
    if (!v.seen.empty()) colour /= double(v.seen.size());
    sggx_fit fit = fit_sggx(normals);
    // The bins' shares and mean directions.
    std::array<double, VX_APP_SIX_WORDS> rays{}, hits{};
    std::array<glm::dvec3, VX_APP_SIX_WORDS> direction{};
    for (const ray_outcome& o : v.outcomes) {
        int slot = six_direction_slot(o.direction);
        rays[slot] += 1, hits[slot] += o.hit ? 1 : 0, direction[slot] += glm::dvec3(o.direction);
    }
    auto error = [&](double rho, double gamma) {
        double e = 0;
        for (int b = 0; b < VX_APP_SIX_WORDS; ++b) {
            if (rays[b] == 0) continue;
            double d = sggx_opacity(fit.s, rho, gamma, glm::normalize(direction[b])) - hits[b] / rays[b];
            e += rays[b] * d * d;
        }
        return e;
    };
    // For each gamma, rho by golden-section search (the error is unimodal in rho); keep the best.
    double best_rho = 0, best_gamma = 1, best = error(0, 1);
    for (double gamma : {0.0, 0.25, 0.5, 0.75, 1.0}) {
        double lo = 0, hi = double(VX_APP_SGGX_DENSITY_MAX);
        constexpr double g = 0.6180339887498949;
        for (int i = 0; i < 32; ++i) {
            double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
            if (error(a, gamma) < error(b, gamma)) hi = b;
            else lo = a;
        }
        double rho = 0.5 * (lo + hi), e = error(rho, gamma);
        if (e < best) best = e, best_rho = rho, best_gamma = gamma;
    }
    glm::dvec3 sigma(std::sqrt(fit.s[0][0]), std::sqrt(fit.s[1][1]), std::sqrt(fit.s[2][2]));
    auto correlation = [&](int a, int b) { return float(fit.s[b][a] / std::max(sigma[a] * sigma[b], 1e-12)); };
    return {VX_APP_AVG_WORD0(srgb_code(colour.r), srgb_code(colour.g), srgb_code(colour.b), unorm(best_gamma, 255)),
            unorm(sigma.x, 255) | unorm(sigma.y, 255) << 8 | unorm(sigma.z, 255) << 16 |
                unorm(best_rho / double(VX_APP_SGGX_DENSITY_MAX), 255) << 24,
            snorm(correlation(0, 1), 8) | snorm(correlation(0, 2), 8) << 8 | snorm(correlation(1, 2), 8) << 16};
}

}  // namespace voxray::appearance
