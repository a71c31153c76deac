// See mesh_raster.hpp.
#include "mesh_raster.hpp"

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
            for (int k = 0; k < 3; ++k) rgb[3 * i + std::size_t(k)] = drawn ? f.rgba[4 * i + std::size_t(k)] : sky_rgb[k];
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
    std::uint64_t mismatches = 0, covered = 0, equal = 0;
    for (int view = 0; view < views; ++view) {
        raster_view v = view_of(model, view, 320, 240, 64.0f);
        raster_frame f = raster.draw(v);
        auto primary = primary_rays(v.cam, v.width, v.height);
        std::vector<hit> hits(primary.size());
        rays.closest_hit(primary, hits);
        auto a = check::compare_raster_hits(f.pixels, hits, v.width, v.height);
        mismatches += a.off_edges + a.beyond(0.995);
        covered += a.covered, equal += a.equal;
    }
    std::printf("raster at level 0 on %s against primary hits over %d views of 320 x 240: %llu of %llu covered pixels "
                "equal (%.3f %%); %llu mismatches (differing off an edge, or beyond 0.5 %%)\n",
                raster.device_name().c_str(), views, (unsigned long long)equal, (unsigned long long)covered,
                covered ? 100.0 * double(equal) / double(covered) : 100.0, (unsigned long long)mismatches);
    return mismatches;
}

#else

void write_raster_png(const voxel_model&, const std::vector<meshing::chunk_mesh>&, const raster_options&) {
    fail("--png draws with the Vulkan backend, which this voxray was built without");
}

std::uint64_t check_raster(const voxel_model&, const std::vector<meshing::chunk_mesh>&, int) {
    fail("the raster check draws with the Vulkan backend, which this voxray was built without");
}

#endif

}  // namespace voxray::tool
