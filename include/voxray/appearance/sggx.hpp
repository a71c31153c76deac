// The SGGX fit of a voxel's normals (the paper's section 3.3, after Heitz et al. 2015): the
// frame of the eigenvectors of the mean of n n^T, and the SGGX matrix S whose projected
// area sqrt(w^T S w) stands for how much surface the voxel turns to direction w. The frame's
// octants group the normals into the (up to) eight faces of the paper's octahedron
// (appearance/faces.hpp).
#pragma once
#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

namespace voxray::appearance {

struct eigen3 {
    glm::dvec3 values{0.0};      // descending
    std::array<glm::dvec3, 3> vectors{};  // unit, right-handed, vectors[i] belongs to values[i]
};

// Eigen-decomposition of a symmetric 3x3 matrix by cyclic Jacobi rotations: a few sweeps
// reach double precision for any input, with no special case for repeated eigenvalues.
inline eigen3 symmetric_eigen(glm::dmat3 a) {
    glm::dmat3 v(1.0);
    for (int sweep = 0; sweep < 32; ++sweep) {
        double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        if (off < 1e-30) break;
        for (int p = 0; p < 2; ++p)
            for (int q = p + 1; q < 3; ++q) {
                if (std::fabs(a[p][q]) < 1e-300) continue;
                double theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
                double t = (theta >= 0 ? 1.0 : -1.0) / (std::fabs(theta) + std::sqrt(theta * theta + 1.0));
                double c = 1.0 / std::sqrt(t * t + 1.0), s = t * c;
                glm::dmat3 j(1.0);  // a <- j^T a j zeroes a[p][q]
                j[p][p] = c, j[q][q] = c, j[q][p] = s, j[p][q] = -s;
                a = glm::transpose(j) * a * j;
                v = v * j;
            }
    }
    eigen3 e;
    std::array<int, 3> order{0, 1, 2};
    std::sort(order.begin(), order.end(), [&](int x, int y) { return a[x][x] > a[y][y]; });
    for (int i = 0; i < 3; ++i) e.values[i] = a[order[i]][order[i]], e.vectors[i] = glm::normalize(v[order[i]]);
    if (glm::dot(glm::cross(e.vectors[0], e.vectors[1]), e.vectors[2]) < 0) e.vectors[2] = -e.vectors[2];
    return e;
}

struct sggx_fit {
    std::array<glm::dvec3, 3> frame{glm::dvec3(1, 0, 0), glm::dvec3(0, 1, 0), glm::dvec3(0, 0, 1)};
    glm::dvec3 projected{1.0};  // the projected area along each frame axis, sqrt of S's eigenvalues
    glm::dmat3 s{1.0};          // S = R diag(projected^2) R^T

    double projected_area(glm::dvec3 w) const { return std::sqrt(std::max(glm::dot(w, s * w), 0.0)); }
    // The octant (0..7) of unit normal n in the frame: bit i set where n . frame[i] < 0.
    int octant(glm::dvec3 n) const {
        return (glm::dot(n, frame[0]) < 0 ? 1 : 0) | (glm::dot(n, frame[1]) < 0 ? 2 : 0) |
               (glm::dot(n, frame[2]) < 0 ? 4 : 0);
    }
};

// The fit of unit normals: the frame from the eigenvectors of mean(n n^T); along each axis
// the projected area is the mean |e . n| (at least 0.1, so S stays invertible), as in the
// paper's code. No normals: the isotropic fit.
inline sggx_fit fit_sggx(std::span<const glm::dvec3> normals) {
    sggx_fit f;
    if (normals.empty()) return f;
    glm::dmat3 m(0.0);
    for (glm::dvec3 n : normals) m += glm::outerProduct(n, n);
    eigen3 e = symmetric_eigen(m / double(normals.size()));
    f.frame = e.vectors;
    glm::dmat3 r(f.frame[0], f.frame[1], f.frame[2]), d(0.0);
    for (int i = 0; i < 3; ++i) {
        double mean = 0;
        for (glm::dvec3 n : normals) mean += std::fabs(glm::dot(n, f.frame[i]));
        f.projected[i] = std::max(mean / double(normals.size()), 0.1);
        d[i][i] = f.projected[i] * f.projected[i];
    }
    f.s = r * d * glm::transpose(r);
    return f;
}

}  // namespace voxray::appearance
