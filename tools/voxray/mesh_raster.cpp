// See mesh_raster.hpp.
#include "mesh_raster.hpp"

#include <cmath>
#include <cstdio>

#include "image_writer.hpp"
#include "voxray/core/error.hpp"
#include "voxray/rays/camera.hpp"
#include "voxray/rays/shading.hpp"

#if defined(VOXRAY_LINKED_VULKAN)
#include "voxray/check/raster_hits.hpp"
#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/vulkan/chunk_raster.hpp"
#include "voxray/vulkan/triangle_raster.hpp"
#endif

namespace voxray::tool {

#if defined(VOXRAY_LINKED_VULKAN)

namespace {

std::vector<std::uint32_t> palette_colours(const palette& p) {
    std::vector<std::uint32_t> colours(palette::size);
    for (int i = 0; i < palette::size; ++i) colours[std::size_t(i)] = pack_rgba(p[std::uint8_t(i)].colour);
    return colours;
}

raster_view view_of(const voxel_model& model, int view, int width, int height, float lod_bias) {
    return {.cam = auto_camera(model.bounds(), model.up_axis, view), .width = width, .height = height,
            .lod_bias = lod_bias, .to_sun = sun_direction(model.up_axis)};
}

}  // namespace

void write_raster_png(const voxel_model& model, const std::vector<meshing::chunk_mesh>& meshes,
                      const raster_options& o) {
    chunk_rasterizer raster;
    raster.upload(meshes, palette_colours(model.palette()));
    raster_view v = view_of(model, o.view, o.width, o.height, o.lod_bias);
    raster_frame f = raster.draw(v);
    camera_frame basis(v.cam, v.width, v.height);
    std::vector<std::uint8_t> rgb(std::size_t(v.width) * std::size_t(v.height) * 3);
    for (int y = 0; y < v.height; ++y)
        for (int x = 0; x < v.width; ++x) {
            std::size_t i = std::size_t(y) * std::size_t(v.width) + std::size_t(x);
            bool drawn = f.rgba[4 * i + 3] != 0;
            auto sky_rgb = to_srgb8(sky(basis.pixel(x, y).direction, model.up_axis));
            for (std::size_t k = 0; k < 3; ++k) rgb[3 * i + k] = drawn ? f.rgba[4 * i + k] : sky_rgb[k];
        }
    write_image(o.png, v.width, v.height, rgb);
    std::printf("raster on %s: %u draws (%u face ranges culled), %llu quads at LOD bias %g, %.2f ms on the device, "
                "%.2f ms in all -> %s\n",
                raster.device_name().c_str(), f.draws, f.culled, (unsigned long long)f.quads, double(o.lod_bias),
                f.gpu_ms, f.ms, o.png.c_str());
}

std::uint64_t check_raster(const voxel_model& model, const std::vector<meshing::chunk_mesh>& meshes, int views) {
    chunk_rasterizer raster;
    raster.upload(meshes, palette_colours(model.palette()));
    dense_grid grid(model);
    tracer<cpu, dense_grid> rays(grid);
    check::raster_agreement all;
    for (int view = 0; view < views; ++view) {
        raster_view v = view_of(model, view, 320, 240, 64.0f);
        raster_frame f = raster.draw(v);
        auto primary = primary_rays(v.cam, v.width, v.height);
        std::vector<hit> hits(primary.size());
        rays.closest_hit(primary, hits);
        auto a = check::compare_raster_hits(f.pixels, hits, v.width, v.height);
        all.off_edges += a.off_edges, all.covered += a.covered, all.equal += a.equal;
    }
    // The share is over all views' covered pixels, as printed: one view of a scene whose voxels
    // are smaller than its pixels is nearly all edges, where the two may differ.
    std::uint64_t mismatches = all.off_edges + all.beyond(0.995), covered = all.covered, equal = all.equal;
    std::printf("raster at level 0 on %s against primary hits over %d views of 320 x 240: %llu of %llu covered pixels "
                "equal (%.3f %%); %llu mismatches (differing off an edge, or beyond 0.5 %%)\n",
                raster.device_name().c_str(), views, (unsigned long long)equal, (unsigned long long)covered,
                covered ? 100.0 * double(equal) / double(covered) : 100.0, (unsigned long long)mismatches);
    return mismatches;
}

namespace {

// Pixels either picture covers, and the RMS of their colour differences (8-bit units).
double rmse(const raster_frame& a, const raster_frame& b) {
    double sum = 0;
    std::uint64_t covered = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        if (a.rgba[4 * i + 3] == 0 && b.rgba[4 * i + 3] == 0) continue;
        ++covered;
        for (std::size_t k = 0; k < 3; ++k) {
            double d = double(a.rgba[4 * i + k]) - double(b.rgba[4 * i + k]);
            sum += d * d;
        }
    }
    return covered ? std::sqrt(sum / (3.0 * double(covered))) : 0.0;
}

constexpr std::uint32_t grey = 0xFFB4B4B4u;

}  // namespace

struct level_images::state {
    chunk_rasterizer chunks;
    triangle_rasterizer triangles;
    raster_view view;
    raster_frame level0;
};

level_images::level_images(const std::vector<meshing::chunk_mesh>& meshes, int up_axis)
    : state_(std::make_unique<state>()) {
    box3i bounds{glm::ivec3(0), glm::ivec3(0)};
    for (std::size_t i = 0; i < meshes.size(); ++i) {
        box3i chunk{meshes[i].origin, meshes[i].origin + VX_MESH_CHUNK_EDGE};
        bounds = i ? box3i{glm::min(bounds.min, chunk.min), glm::max(bounds.max, chunk.max)} : chunk;
    }
    std::vector<std::uint32_t> colours(1u << 16, grey);
    state_->chunks.upload(meshes, colours);
    state_->view = {.cam = auto_camera(bounds, up_axis), .width = 512, .height = 288, .fixed_level = 0,
                    .to_sun = sun_direction(up_axis)};
    state_->level0 = state_->chunks.draw(state_->view);
}

level_images::~level_images() = default;

bool level_images::available() const { return true; }

double level_images::pop_rmse(int level) {
    raster_view v = state_->view;
    v.fixed_level = level;
    return rmse(state_->chunks.draw(v), state_->level0);
}

double level_images::triangles_rmse(std::span<const float> positions, std::span<const std::uint32_t> indices) {
    state_->triangles.upload(positions, indices, grey);
    return rmse(state_->triangles.draw(state_->view), state_->level0);
}

#else

struct level_images::state {};
level_images::level_images(const std::vector<meshing::chunk_mesh>&, int) {}
level_images::~level_images() = default;
bool level_images::available() const { return false; }
double level_images::pop_rmse(int) { return NAN; }
double level_images::triangles_rmse(std::span<const float>, std::span<const std::uint32_t>) { return NAN; }

void write_raster_png(const voxel_model&, const std::vector<meshing::chunk_mesh>&, const raster_options&) {
    fail("--png draws with the Vulkan backend, which this voxray was built without");
}

std::uint64_t check_raster(const voxel_model&, const std::vector<meshing::chunk_mesh>&, int) {
    fail("the raster check draws with the Vulkan backend, which this voxray was built without");
}

#endif

}  // namespace voxray::tool
