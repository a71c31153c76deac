// Terrain with buildings: a size x size footprint (x, y), Z up, heights from
// fractal value noise, a sea, and a few hundred hollow buildings in clusters.
// Realistic for ray tracing: large empty sky, a thin surface, fine detail.
//
// Columns are not solid down to z = 0 (a 1024 footprint would be ~100 M voxels,
// all hidden). Each column keeps a skin of `skin` voxels under its top, and
// reaches further down wherever a neighbour is lower, so slopes and cliffs stay
// closed from every side; the outer rim is solid to z = 0 (a diorama's cut).
//
//   column section:   z = h   grass/sand/rock/snow   (depth 0)
//                     h-1..h-2 dirt/sand/rock        (depth 1..2)
//                     below   deep rock              (down to the skin or the lowest neighbour + 1)
//
// Buildings sit on flat ground above the sea, on a solid foundation. Walls and
// floor slabs are one voxel thick, a floor every 5 voxels (4 of air); windows
// and a door are holes, so rays reach the interior floors. Seeded and
// deterministic: the same options give the same voxels on any machine.
#pragma once
#include <algorithm>
#include <cstdint>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/model/build_threads.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/scenes/parallel_fill.hpp"
#include "voxray/scenes/noise.hpp"

namespace voxray::scenes {

struct terrain_options {
    int size = 1024;         // footprint edge in voxels, 64..8192
    std::uint64_t seed = 1;
    int skin = 4;            // solid voxels under each column's top, 1..64
    unsigned threads = 0;    // 0: all hardware threads
};

namespace terrain_detail {

// Palette layout (indices into the model palette).
enum : std::uint8_t {
    grass = 1, /* 1..3: three shades */ rock = 4, /* 4..5 */ sand = 6, snow = 7, dirt = 8, deep_rock = 9,
    water = 10, foundation = 11, floor_slab = 12, roof = 13, wall = 14 /* 14..19: six facade colours */
};
inline constexpr int wall_colours = 6;
inline constexpr int floor_height = 5;  // slab + 4 voxels of air
// Hash tags: one per use of the seed, so changing one feature leaves the others.
enum : std::uint64_t { tag_height = 100, tag_city = 200, tag_lot = 300, tag_shade = 400, tag_snow = 500 };

struct building {
    int x0, y0, w, d;         // footprint [x0, x0 + w) x [y0, y0 + d)
    int low, base, floors;    // foundation from `low`, ground floor slab at `base`
    std::uint8_t facade;
    int top() const { return base + floors * floor_height; }  // roof slab; parapet at top() + 1
};

// Voxel of building b at (x, y, z) inside its footprint: 0 for air.
inline std::uint8_t building_voxel(const building& b, int x, int y, int z) {
    if (z < b.low || z > b.top() + 1) return 0;
    if (z < b.base) return foundation;
    int lx = x - b.x0, ly = y - b.y0, rel = z - b.base;
    bool wx = lx == 0 || lx == b.w - 1, wy = ly == 0 || ly == b.d - 1;
    if (z == b.top() + 1) return (wx || wy) ? roof : 0;  // parapet
    if (rel % floor_height == 0) return z == b.top() ? roof : floor_slab;
    if (!wx && !wy) return 0;  // interior air
    // Along-wall coordinate; corners (both walls) stay solid.
    int t = wy ? lx : ly, len = wy ? b.w : b.d;
    if (wx && wy) return b.facade;
    int level = rel % floor_height;
    bool front = ly == 0 && !wx;
    if (front && rel < floor_height && level <= 3 && std::abs(2 * t - len + 1) <= 2) return 0;  // door
    if ((level == 2 || level == 3) && t >= 2 && t <= len - 3 && (t - 2) % 4 < 2) return 0;    // window
    return b.facade;
}

}  // namespace terrain_detail

inline voxel_model make_terrain(const terrain_options& opt = {}) {
    using namespace terrain_detail;
    if (opt.size < 64 || opt.size > 8192) fail("terrain size ", opt.size, " is outside 64..8192");
    if (opt.skin < 1 || opt.skin > 64) fail("terrain skin ", opt.skin, " is outside 1..64");
    const int n = opt.size;
    const int max_height = n / 5, sea = max_height * 9 / 50;
    unsigned threads = resolve_build_threads(opt.threads, std::size_t(n));

    // Heightfield (2-D, n^2 shorts), rows in parallel.
    std::vector<std::int16_t> height(std::size_t(n) * n);
    {
        // Broad shape from a few low octaves, squared so lowland is wide and flat;
        // fine detail scaled by height, so plains stay smooth and mountains rough.
        const double broad = n / 3.0, fine = 48.0;
        auto rows = [&](unsigned id) {
            for (int y = int(id); y < n; y += int(threads))
                for (int x = 0; x < n; ++x) {
                    double f = fbm(opt.seed, tag_height, x / broad, y / broad, 4);
                    double g = std::clamp((f - 0.2) / 0.6, 0.0, 1.0);  // fbm clusters near 0.5: stretch
                    double detail = fbm(opt.seed, tag_height + 10, x / fine, y / fine, 4) - 0.5;
                    double h = (max_height - 3) * g * g + detail * (4.0 + 0.25 * max_height * g);
                    height[std::size_t(y) * n + x] = std::int16_t(std::clamp(3.0 + std::floor(h), 1.0, double(max_height)));
                }
        };
        run_build_threads(threads, rows);
    }
    auto H = [&](int x, int y) { return int(height[std::size_t(y) * n + x]); };
    // Lowest solid voxel of a column: the skin, or one above the lowest neighbour.
    auto low = [&](int x, int y) {
        if (x == 0 || y == 0 || x == n - 1 || y == n - 1) return 0;
        int nb = std::min({H(x - 1, y), H(x + 1, y), H(x, y - 1), H(x, y + 1)});
        return std::max(0, std::min(H(x, y) - opt.skin + 1, nb + 1));
    };

    // Buildings: one candidate per 40 x 40 lot, kept where a low-frequency "city"
    // noise is high and the ground is dry and flat enough.
    constexpr int lot = 40;
    std::vector<building> buildings;
    for (int j = 0; j + 1 < n / lot; ++j)
        for (int i = 0; i + 1 < n / lot; ++i) {
            rng r{hash(opt.seed, tag_lot, i, j)};
            double city = fbm(opt.seed, tag_city, (i + 0.5) * lot / (n / 3.0), (j + 0.5) * lot / (n / 3.0), 3);
            if (city < 0.46 || r.uniform() > 0.9) continue;
            building b{};
            b.w = r.range(12, 32), b.d = r.range(12, 32);
            b.x0 = i * lot + r.range(2, lot - b.w - 2);
            b.y0 = j * lot + r.range(2, lot - b.d - 2);
            int hmin = 1 << 30, hmax = 0;
            for (int y = b.y0; y < b.y0 + b.d; ++y)
                for (int x = b.x0; x < b.x0 + b.w; ++x) hmin = std::min(hmin, H(x, y)), hmax = std::max(hmax, H(x, y));
            if (hmin <= sea + 2 || hmax - hmin > 20) continue;
            b.low = std::max(0, hmin - opt.skin + 1);
            b.base = hmax + 1;
            b.floors = 2 + int((city - 0.46) * 50.0 * r.uniform()) + r.range(0, 3);
            b.facade = std::uint8_t(wall + r.range(0, wall_colours - 1));
            buildings.push_back(b);
        }

    // Chunk columns: z range from the columns' lows to the highest content, and
    // the buildings each one touches.
    const int edge = voxel_model::chunk_edge, chunks = (n + edge - 1) / edge;
    std::vector<std::vector<int>> touching(std::size_t(chunks) * chunks);
    std::vector<chunk_column_job> jobs(std::size_t(chunks) * chunks);
    for (int cy = 0; cy < chunks; ++cy)
        for (int cx = 0; cx < chunks; ++cx) {
            int zlo = 1 << 30, zhi = sea;
            for (int y = cy * edge; y < std::min(n, cy * edge + edge); ++y)
                for (int x = cx * edge; x < std::min(n, cx * edge + edge); ++x)
                    zlo = std::min(zlo, low(x, y)), zhi = std::max(zhi, H(x, y));
            jobs[std::size_t(cy) * chunks + cx] = {cx, cy, zlo / edge, zhi / edge};
        }
    for (std::size_t k = 0; k < buildings.size(); ++k) {
        auto& b = buildings[k];
        for (int cy = b.y0 / edge; cy <= (b.y0 + b.d - 1) / edge; ++cy)
            for (int cx = b.x0 / edge; cx <= (b.x0 + b.w - 1) / edge; ++cx) {
                auto& job = jobs[std::size_t(cy) * chunks + cx];
                job.cz0 = std::min(job.cz0, b.low / edge);
                job.cz1 = std::max(job.cz1, (b.top() + 1) / edge);
                touching[std::size_t(cy) * chunks + cx].push_back(int(k));
            }
    }

    voxel_model model;
    model.up_axis = 2;
    auto& pal = model.palette();
    const rgba colours[] = {{0, 0, 0, 0},        {96, 142, 62, 255},  {110, 156, 70, 255}, {82, 128, 58, 255},
                            {128, 122, 114, 255}, {108, 102, 96, 255}, {218, 202, 150, 255}, {240, 244, 248, 255},
                            {120, 92, 64, 255},   {88, 84, 80, 255},   {64, 120, 170, 255},  {150, 146, 140, 255},
                            {176, 172, 164, 255}, {72, 70, 74, 255},   {200, 196, 186, 255}, {170, 84, 62, 255},
                            {214, 186, 140, 255}, {236, 234, 226, 255}, {118, 136, 152, 255}, {156, 110, 80, 255}};
    for (int i = 1; i < int(std::size(colours)); ++i) pal[std::uint8_t(i)].colour = colours[i];

    build_chunks(model, jobs, threads, [&](glm::ivec3 cc, voxel_model::chunk& c) {
        glm::ivec3 o = cc * edge;
        auto put = [&](int x, int y, int z, std::uint8_t v) {
            c.voxels[std::size_t(voxel_model::local_index({x - o.x, y - o.y, z - o.z}))] = v;
        };
        for (int y = o.y; y < std::min(n, o.y + edge); ++y)
            for (int x = o.x; x < std::min(n, o.x + edge); ++x) {
                int h = H(x, y), lo = low(x, y);
                int slope = 0;
                if (x > 0 && y > 0 && x < n - 1 && y < n - 1)
                    slope = std::max({std::abs(h - H(x - 1, y)), std::abs(h - H(x + 1, y)), std::abs(h - H(x, y - 1)),
                                      std::abs(h - H(x, y + 1))});
                // Surface material: sand by the sea, rock on steep ground, snow up high.
                double snow_line = max_height * (0.7 + 0.1 * value_noise(opt.seed, tag_snow, x / 24.0, y / 24.0));
                std::uint8_t top = grass, under = dirt;
                if (h <= sea + 1) top = under = sand;
                else if (h > snow_line) top = snow, under = rock;
                else if (slope >= 3) top = under = rock;
                std::uint64_t speck = hash(opt.seed, tag_shade, x, y);
                if (top == grass) top = std::uint8_t(grass + speck % 3);
                if (top == rock) top = std::uint8_t(rock + (speck >> 8) % 2);
                for (int z = std::max(lo, o.z); z <= std::min(h, o.z + edge - 1); ++z)
                    put(x, y, z, z == h ? top : z >= h - 2 ? under : std::uint8_t(deep_rock));
                if (h < sea && sea >= o.z && sea < o.z + edge) put(x, y, sea, water);
            }
        for (int k : touching[std::size_t(cc.y) * chunks + cc.x]) {
            auto& b = buildings[std::size_t(k)];
            for (int y = std::max(b.y0, o.y); y < std::min(b.y0 + b.d, o.y + edge); ++y)
                for (int x = std::max(b.x0, o.x); x < std::min(b.x0 + b.w, o.x + edge); ++x)
                    for (int z = std::max(b.low, o.z); z <= std::min(b.top() + 1, o.z + edge - 1); ++z)
                        if (auto v = building_voxel(b, x, y, z)) put(x, y, z, v);
        }
    });
    return model;
}

}  // namespace voxray::scenes
