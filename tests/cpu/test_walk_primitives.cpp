// The shared walk primitives of kernels/dda.h against the reference walk over voxels:
// leaving an empty box in one move (vx_dda_leave_box) and descending into a cell
// (vx_dda_reenter) must land on the very cell, t, face and next crossings that stepping
// voxel by voxel (vx_dda_move) reaches, bit for bit, on every lane set.
#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <string>

#include "voxray/check/ray_sets.hpp"
#include "voxray/cpu/lanes.hpp"

namespace {

using namespace voxray::kernels::scalar;

constexpr int extent = 64;

vx_ray random_ray(voxray::rng& g) {
    vx_ray r{};
    r.ox = g.uniform(1.0f, extent - 1.0f);
    r.oy = g.uniform(1.0f, extent - 1.0f);
    r.oz = g.uniform(1.0f, extent - 1.0f);
    float d[3];
    for (float& c : d) {
        switch (g.below(6)) {
        case 0: c = 0.0f; break;  // axis-parallel
        case 1: c = g.below(2) ? 1.0f : -1.0f; break;  // diagonals: ties at every corner
        default: c = g.uniform(-1.0f, 1.0f); break;
        }
    }
    if (d[0] == 0.0f && d[1] == 0.0f && d[2] == 0.0f) d[0] = 0.5f;
    // Origins on voxel planes make exact ties between axes likely.
    if (g.below(4) == 0) r.ox = std::floor(r.ox);
    if (g.below(4) == 0) r.oy = std::floor(r.oy);
    r.dx = d[0], r.dy = d[1], r.dz = d[2];
    r.tmin = 0.0f;
    r.tmax = INFINITY;
    return r;
}

void expect_same_walk(const vx_dda& a, const vx_dda& b, int i) {
    EXPECT_EQ(a.cx, b.cx) << "ray " << i;
    EXPECT_EQ(a.cy, b.cy) << "ray " << i;
    EXPECT_EQ(a.cz, b.cz) << "ray " << i;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(a.t), std::bit_cast<std::uint32_t>(b.t)) << "ray " << i;
    EXPECT_EQ(a.face, b.face) << "ray " << i;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(a.nx), std::bit_cast<std::uint32_t>(b.nx)) << "ray " << i;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(a.ny), std::bit_cast<std::uint32_t>(b.ny)) << "ray " << i;
    EXPECT_EQ(std::bit_cast<std::uint32_t>(a.nz), std::bit_cast<std::uint32_t>(b.nz)) << "ray " << i;
}

bool inside(const vx_dda& d, const int lo[3], const int hi[3]) {
    return d.cx >= lo[0] && d.cx < hi[0] && d.cy >= lo[1] && d.cy < hi[1] && d.cz >= lo[2] && d.cz < hi[2];
}

TEST(walk_primitives, leaving_a_box_lands_where_the_voxel_walk_does) {
    voxray::rng g(17);
    int checked = 0;
    for (int i = 0; i < 20000; ++i) {
        vx_ray r = random_ray(g);
        vx_dda d = vx_dda_begin_scaled(r, 0, 0, 0, extent, extent, extent, 1.0f);
        ASSERT_EQ(d.status, VX_STATUS_ACTIVE);
        int c[3] = {d.cx, d.cy, d.cz}, lo[3], hi[3];
        for (int a = 0; a < 3; ++a) {
            lo[a] = std::max(0, c[a] - int(g.below(6)));
            hi[a] = std::min(extent, c[a] + 1 + int(g.below(6)));
        }
        vx_dda walk = d;
        while (walk.status == VX_STATUS_ACTIVE && inside(walk, lo, hi)) walk = vx_dda_move(walk, true);
        vx_dda jump = vx_dda_leave_box(d, r.dx, r.dy, r.dz, lo[0], lo[1], lo[2], hi[0], hi[1], hi[2], true);
        expect_same_walk(jump, walk, i);
        if (HasFailure()) return;
        ++checked;
    }
    EXPECT_EQ(checked, 20000);
}

TEST(walk_primitives, descending_into_a_cell_lands_where_the_voxel_walk_does) {
    voxray::rng g(23);
    for (int sub : {1, 2, 4}) {
        const int size = 16;
        for (int i = 0; i < 20000; ++i) {
            vx_ray r = random_ray(g);
            // The coarse walk over cells of `size` voxels, expressed in voxel units (as the
            // brickmap does), against the voxel walk of the same ray.
            vx_dda coarse = vx_dda_begin_scaled(r, 0, 0, 0, extent / size, extent / size, extent / size, float(size));
            coarse.ox *= size, coarse.oy *= size, coarse.oz *= size;
            coarse.ix /= size, coarse.iy /= size, coarse.iz /= size;
            coarse.cx *= size, coarse.cy *= size, coarse.cz *= size;
            int moves = int(g.below(3));
            for (int k = 0; k < moves && coarse.status == VX_STATUS_ACTIVE; ++k)
                coarse = vx_dda_move_sized(coarse, true, size);
            if (coarse.status != VX_STATUS_ACTIVE || coarse.cx < 0 || coarse.cy < 0 || coarse.cz < 0 ||
                coarse.cx >= extent || coarse.cy >= extent || coarse.cz >= extent)
                continue;
            vx_dda fine = vx_dda_reenter(coarse, r.dx, r.dy, r.dz, size, sub, true);
            // The reference: the voxel walk until it enters the coarse cell (at t = coarse.t,
            // after any zero-length moves at that t), in sub-cells.
            int lo[3] = {coarse.cx, coarse.cy, coarse.cz}, hi[3] = {lo[0] + size, lo[1] + size, lo[2] + size};
            vx_dda walk = vx_dda_begin_scaled(r, 0, 0, 0, extent, extent, extent, 1.0f);
            while (walk.status == VX_STATUS_ACTIVE && (walk.t < coarse.t || !inside(walk, lo, hi)))
                walk = vx_dda_move(walk, true);
            ASSERT_EQ(walk.t, coarse.t) << "ray " << i;
            auto where = [&] {
                char text[320];
                std::snprintf(text, sizeof text, "ray %d, sub %d: o (%.9g %.9g %.9g) d (%.9g %.9g %.9g), cell (%d %d %d) "
                              "entered at t %.9g through face %u", i, sub, r.ox, r.oy, r.oz, r.dx, r.dy, r.dz,
                              coarse.cx, coarse.cy, coarse.cz, coarse.t, coarse.face);
                return std::string(text);
            };
            EXPECT_EQ(fine.cx, walk.cx / sub * sub) << where();
            EXPECT_EQ(fine.cy, walk.cy / sub * sub) << where();
            EXPECT_EQ(fine.cz, walk.cz / sub * sub) << where();
            if (HasFailure()) return;
        }
    }
}

}  // namespace
