// Exact triangle / axis-aligned box overlap by the separating axis theorem
// (Akenine-Moller): two convex shapes are disjoint iff some axis separates their
// projections, and for a triangle and a box it suffices to try 13 axes:
//   3 box face normals, the triangle normal, 9 cross products box-axis x edge.
// Boxes are closed: a triangle that only touches a face, edge or corner overlaps.
// That makes surface voxelization conservative (no gaps where a triangle runs
// exactly along a voxel boundary). Double precision throughout, and every
// comparison allows a relative slack of 2^-40 of the magnitudes involved, so
// rounding can only add a voxel that touches to within ~1e-12, never drop one.
#pragma once
#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

namespace voxray::io {

// Relative slack of the comparisons (see above).
inline constexpr double triangle_box_slack = 0x1.0p-40;

// General form: box given by centre and half size.
inline bool triangle_box_overlap(glm::dvec3 centre, glm::dvec3 half, glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) {
    const glm::dvec3 v[3] = {a - centre, b - centre, c - centre};
    glm::dvec3 mag = glm::max(glm::abs(centre), glm::max(glm::abs(a), glm::max(glm::abs(b), glm::abs(c)))) + half;
    // Box face normals: bounding-box rejection.
    for (int i = 0; i < 3; ++i) {
        double lo = std::min({v[0][i], v[1][i], v[2][i]}), hi = std::max({v[0][i], v[1][i], v[2][i]});
        double r = half[i] + triangle_box_slack * mag[i];
        if (lo > r || hi < -r) return false;
    }
    const glm::dvec3 e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
    auto separated = [&](glm::dvec3 axis) {
        double p0 = glm::dot(axis, v[0]), p1 = glm::dot(axis, v[1]), p2 = glm::dot(axis, v[2]);
        glm::dvec3 aa = glm::abs(axis);
        double r = glm::dot(half, aa) + triangle_box_slack * glm::dot(mag, aa) * 4.0;
        return std::min({p0, p1, p2}) > r || std::max({p0, p1, p2}) < -r;
    };
    for (int k = 0; k < 3; ++k) {
        if (separated({0.0, -e[k].z, e[k].y})) return false;  // x axis cross edge
        if (separated({e[k].z, 0.0, -e[k].x})) return false;  // y axis cross edge
        if (separated({-e[k].y, e[k].x, 0.0})) return false;  // z axis cross edge
    }
    return !separated(glm::cross(e[0], e[1]));  // triangle normal
}

// The same test specialised for unit cells [m, m+1]^3 of one triangle, set up once
// and then run for many cells. Each of the 13 axes becomes "lo <= dot(axis, m) <= hi"
// with lo/hi precomputed, so a cell costs a few multiply-adds and compares.
class triangle_cell_test {
public:
    triangle_cell_test(glm::dvec3 a, glm::dvec3 b, glm::dvec3 c) : v_{a, b, c} {
        bmin_ = glm::min(a, glm::min(b, c));
        bmax_ = glm::max(a, glm::max(b, c));
        // Cells near the triangle have coordinates of about the same magnitude.
        mag_ = glm::max(glm::abs(bmin_), glm::abs(bmax_)) + 1.0;
        const glm::dvec3 e[3] = {b - a, c - b, a - c};
        normal_ = glm::cross(e[0], e[1]);
        int n = 0;
        for (int k = 0; k < 3; ++k) {
            add(n++, {0.0, -e[k].z, e[k].y});
            add(n++, {e[k].z, 0.0, -e[k].x});
            add(n++, {-e[k].y, e[k].x, 0.0});
        }
        add(n, normal_);
    }

    // Cell m covers [m, m+1] on each axis.
    bool overlaps(glm::dvec3 m) const {
        for (int i = 0; i < 3; ++i) {
            double slack = triangle_box_slack * mag_[i];
            if (m[i] > bmax_[i] + slack || m[i] + 1.0 < bmin_[i] - slack) return false;
        }
        return overlaps_planes(m);
    }
    // Skips the bounding-box axes: for callers whose cell range already comes
    // from the closed bounding box.
    bool overlaps_planes(glm::dvec3 m) const {
        for (auto& t : axes_) {
            double q = glm::dot(t.axis, m);
            if (q < t.lo || q > t.hi) return false;
        }
        return true;
    }

    glm::dvec3 normal() const { return normal_; }
    glm::dvec3 bmin() const { return bmin_; }
    glm::dvec3 bmax() const { return bmax_; }
    const glm::dvec3& vertex(int k) const { return v_[k]; }

private:
    struct axis_test {
        glm::dvec3 axis{0.0};
        double lo = 0, hi = 0;
    };
    // Cell projection onto `axis` is dot(axis, m) + [neg, pos] (neg/pos: sums of the
    // negative/positive components); it meets the triangle's [pmin, pmax] iff
    // dot(axis, m) lies in [pmin - pos, pmax - neg].
    void add(int i, glm::dvec3 axis) {
        double p0 = glm::dot(axis, v_[0]), p1 = glm::dot(axis, v_[1]), p2 = glm::dot(axis, v_[2]);
        double pos = 0, neg = 0;
        for (int k = 0; k < 3; ++k) (axis[k] > 0 ? pos : neg) += axis[k];
        double slack = triangle_box_slack * glm::dot(mag_, glm::abs(axis)) * 4.0;
        axes_[i] = {axis, std::min({p0, p1, p2}) - pos - slack, std::max({p0, p1, p2}) - neg + slack};
    }

    glm::dvec3 v_[3];
    glm::dvec3 bmin_, bmax_, normal_, mag_;
    axis_test axes_[10];
};

}  // namespace voxray::io
