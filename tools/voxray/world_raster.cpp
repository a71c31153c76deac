// See world_raster.hpp.
#include "world_raster.hpp"

#include <algorithm>
#include <chrono>
#include <map>
#include <unordered_map>

#include "voxray/core/error.hpp"
#include "voxray/rays/shading.hpp"

#if defined(VOXRAY_LINKED_VULKAN)
#include "voxray/meshing/mesher.hpp"
#include "voxray/meshing/squashed.hpp"
#include "voxray/meshing/world_chunk_source.hpp"
#include "voxray/vulkan/chunk_raster.hpp"
#endif

namespace voxray::tool {

#if defined(VOXRAY_LINKED_VULKAN)

namespace {

// A shown chunk's box in world voxels.
box3i chunk_world_box(const world_grid& grid, const chunk_key& k) {
    glm::ivec3 lo = grid.origin + k.cell * (grid.edge() << k.lod);
    return {lo, lo + (grid.edge() << k.lod)};
}

// The nearest palette entry (1..255) to an RGBA8 colour, by RGB distance.
std::uint8_t nearest_entry(const palette& pal, std::uint32_t colour) {
    int best = 1;
    long best_d = -1;
    for (int i = 1; i < palette::size; ++i) {
        rgba c = pal[std::uint8_t(i)].colour;
        long dr = long(colour & 255u) - c.r, dg = long((colour >> 8) & 255u) - c.g;
        long db = long((colour >> 16) & 255u) - c.b;
        long d = dr * dr + dg * dg + db * db;
        if (best_d < 0 || d < best_d) best = i, best_d = d;
    }
    return std::uint8_t(best);
}

bool same_boxes(const std::vector<box3i>& a, const std::vector<box3i>& b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                      [](const box3i& x, const box3i& y) { return x.min == y.min && x.max == y.max; });
}

}  // namespace

struct world_raster::state {
    state(const palette& p, bool c, int u, float b) : pal(p), colours(c), up_axis(u), lod_bias(b) {
        for (int i = 0; i < palette::size; ++i) rgba8[std::size_t(i)] = pack_rgba(pal[std::uint8_t(i)].colour);
    }
    palette pal;
    std::vector<std::uint32_t> rgba8 = std::vector<std::uint32_t>(palette::size);  // the raster's colour table
    bool colours;
    int up_axis;
    float lod_bias;
    chunk_rasterizer raster;
    meshing::mesher mesher;
    std::unordered_map<std::uint32_t, std::uint8_t> nearest;
    // Meshes of the shown chunks, with the finer chunks cut out of each when it was meshed.
    struct meshed {
        std::vector<box3i> cut;
        std::vector<meshing::chunk_mesh> meshes;
    };
    std::map<chunk_key, meshed, chunk_key_less> cache;
    bool uploaded = false;  // the rasterizer holds the cache's meshes
};

world_raster::world_raster(const palette& pal, bool colours, int up_axis, float lod_bias)
    : state_(std::make_unique<state>(pal, colours, up_axis, lod_bias)) {}

world_raster::~world_raster() = default;

world_raster_frame world_raster::draw(const streamed_world& world, const camera& cam, int width, int height) {
    state& s = *state_;
    world_raster_frame out;
    auto start = std::chrono::steady_clock::now();
    const world_grid& grid = world.manifest().grid;
    auto shown = world.residency().placements();
    out.chunks_shown = shown.size();
    std::map<chunk_key, state::meshed, chunk_key_less> next;
    for (const placement& p : shown) {
        if (!p.chunk || p.chunk->empty()) continue;
        box3i box = chunk_world_box(grid, p.key);
        // Finer shown chunks inside this one, in its cells.
        std::vector<box3i> cut;
        for (const placement& q : shown)
            if (q.key.lod < p.key.lod) {
                box3i fine = chunk_world_box(grid, q.key);
                bool inside = glm::all(glm::greaterThanEqual(fine.min, box.min)) &&
                              glm::all(glm::lessThanEqual(fine.max, box.max));
                if (inside)
                    cut.push_back({(fine.min - box.min) >> p.key.lod, (fine.max - box.min) >> p.key.lod});
            }
        auto cached = s.cache.find(p.key);
        if (cached != s.cache.end() && same_boxes(cached->second.cut, cut)) {
            next[p.key] = std::move(cached->second);
            continue;
        }
        meshing::world_chunk_source source(*p.chunk, [&](std::uint32_t value) -> std::uint8_t {
            if (!s.colours) return std::uint8_t(value);
            auto [it, added] = s.nearest.try_emplace(value, 0);
            if (added) it->second = nearest_entry(s.pal, value);
            return it->second;
        });
        for (const box3i& c : cut) source.clear(c);
        state::meshed m{cut, {}};
        meshing::chunk_voxels chunk;
        std::vector<std::uint8_t> scratch;
        for (glm::ivec3 origin : source.mesh_origins()) {
            meshing::fill_chunk(source, origin, chunk, scratch);
            s.mesher.mesh(chunk, m.meshes.emplace_back());
            meshing::remove_squashed_faces(m.meshes.back());
        }
        next[p.key] = std::move(m);
        ++out.chunks_meshed;
    }
    // Every kept chunk came from the cache: the shown set changed only if one was meshed or dropped.
    bool changed = !s.uploaded || out.chunks_meshed > 0 || next.size() != s.cache.size();
    s.cache = std::move(next);
    if (changed) {
        std::vector<meshing::chunk_mesh> meshes;
        std::vector<chunk_placement> placements;
        for (auto& [key, m] : s.cache)
            for (auto& mesh : m.meshes) {
                meshes.push_back(mesh);
                placements.push_back({chunk_world_box(grid, key).min, key.lod});
            }
        s.raster.upload(meshes, s.rgba8, placements);
        s.uploaded = true;
    }
    out.mesh_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    raster_view v{.cam = cam, .width = width, .height = height, .lod_bias = s.lod_bias,
                  .to_sun = sun_direction(s.up_axis)};
    raster_frame f = s.raster.draw(v);
    out.quads = f.quads;
    out.draw_ms = f.gpu_ms;
    camera_frame basis(cam, width, height);
    out.rgb.resize(std::size_t(width) * std::size_t(height) * 3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            std::size_t i = std::size_t(y) * std::size_t(width) + std::size_t(x);
            auto sky_rgb = to_srgb8(sky(basis.pixel(x, y).direction, s.up_axis));
            for (std::size_t k = 0; k < 3; ++k) out.rgb[3 * i + k] = f.rgba[4 * i + 3] ? f.rgba[4 * i + k] : sky_rgb[k];
        }
    return out;
}

#else

struct world_raster::state {};

world_raster::world_raster(const palette&, bool, int, float) {
    fail("world-fly --raster draws with the Vulkan backend, which this voxray was built without");
}
world_raster::~world_raster() = default;
world_raster_frame world_raster::draw(const streamed_world&, const camera&, int, int) { return {}; }

#endif

}  // namespace voxray::tool
