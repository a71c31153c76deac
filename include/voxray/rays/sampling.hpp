// A small seedable random generator and the cosine-weighted hemisphere sample that
// diffuse bounces use.
#pragma once
#include <cmath>
#include <cstdint>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace voxray {

// SplitMix64: tiny, seedable and identical on every platform (std distributions are not),
// so a seed names the same rays everywhere.
class rng {
public:
    explicit rng(std::uint64_t seed) : state_(seed) {}
    std::uint64_t next() {
        std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
    float uniform() { return float(next() >> 40) * (1.0f / 16777216.0f); }  // [0, 1)
    float uniform(float lo, float hi) { return lo + (hi - lo) * uniform(); }
    int below(int n) { return int(next() % std::uint64_t(n)); }

private:
    std::uint64_t state_;
};

// A unit direction around unit normal `n`, cosine-weighted, from two uniforms in [0, 1).
inline glm::vec3 cosine_hemisphere(glm::vec3 n, float u1, float u2) {
    float phi = u2 * 6.2831853f, s = std::sqrt(u1);
    glm::vec3 t = std::abs(n.x) > 0.5f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    glm::vec3 b1 = glm::normalize(glm::cross(n, t)), b2 = glm::cross(n, b1);
    return glm::normalize(b1 * (s * std::cos(phi)) + b2 * (s * std::sin(phi)) + n * std::sqrt(1.0f - u1));
}

}  // namespace voxray
