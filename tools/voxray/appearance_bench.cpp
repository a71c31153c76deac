// voxray appearance-bench: how voxels look from afar against the triangles they replaced
// (issue 25). For one mesh at one resolution: the appearance tables of each method
// precomputed with Embree (bytes and µs a voxel), then for each view and for a light in
// front and one behind, the reference (Embree on the triangles, --reference-spp stratified
// samples a pixel) and every method's picture by the compositing walk (4 rays a pixel):
// averages, SGGX, six directions (made for each light) and ours (the compact record), and
// with --lod ours re-sampled from the level at twice the resolution (appearance/resample.hpp),
// and with --shadows cast shadows in the reference and precomputed ones (appearance/shadows.hpp)
// in every method's walk but six directions' (lit when made),
// compared in sRGB: MSE (all pixels, and the pixels the reference covers), PSNR and SSIM
// (scikit-image's parameters, per channel; scripts/appearance_table.py checks them with
// scikit-image itself). One JSON line per method, view and light after a header line.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "bench_header.hpp"
#include "cli.hpp"
#include "output.hpp"
#include "timing.hpp"
#include "voxray/rays/camera.hpp"

#if VOXRAY_WITH_EMBREE
#include "appearance_pictures.hpp"
#include "appearance_structures.hpp"
#include "voxray/appearance/precompute.hpp"
#include "voxray/appearance/resample.hpp"
#include "voxray/appearance/shadows.hpp"
#include "voxray/cpu/appearance_walk.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/embree/triangle_scene.hpp"
#include "voxray/gltf/coloured_mesh.hpp"
#endif

namespace voxray::tool {

namespace {

struct appearance_bench_options {
    std::string mesh;
    int resolution = 128;
    int size = 0;            // picture side in pixels; 0: the resolution, as in the paper
    int views = 3;
    int reference_side = 16;  // 16 x 16 = 256 samples a pixel (the paper: 1024)
    unsigned threads = 2;
    std::string structure = "dense";  // whose first-hit kernel the walk re-enters
    bool lod = false;                  // also ours re-sampled from the level at twice the resolution
    bool shadows = false;              // cast shadows in the reference, precomputed ones in the walks
    std::string json, images;
};

#if VOXRAY_WITH_EMBREE

struct method_table {
    std::string name;
    appearance::appearance_table table;
    appearance::precompute_stats stats;
    double shadow_us_per_voxel = 0;  // the precomputed shadows' time, where it has them
};

method_table precompute_method(const embree::triangle_scene& scene, const io::triangle_mesh& mesh,
                               const voxel_model& model, const char* name, appearance::record_kind kind,
                               const shading& light, unsigned threads) {
    method_table m{name, {}, {}, 0};
    m.table = appearance::precompute(
        scene, mesh, model,
        {.kind = kind, .sampling = {}, .threads = threads, .light = {light.to_light, light.ambient}}, &m.stats);
    return m;
}

struct walked_picture {
    linear_picture picture;
    double seconds = 0, steps = 0, visits = 0;  // steps and visits: means a ray
};

// Ours at `resolution`, re-sampled through the walk from ours at twice it (made from the
// triangles there): a LOD level as a chain builds it. Its voxels are the
// finer level's coarser_voxels, so it has a structure of its own (`structure`).
method_table resampled_method(const io::triangle_mesh& mesh, int resolution, const std::string& structure_name,
                              unsigned threads, walk_structure& structure) {
    voxel_model fine = io::voxelize(mesh, {.resolution = 2 * resolution, .threads = threads});
    embree::triangle_scene fine_scene(mesh, io::make_grid_map(mesh.bounds(), 2 * resolution));
    const appearance::precompute_options o{.kind = appearance::record_kind::compact, .threads = threads};
    appearance::appearance_table fine_table = appearance::precompute(fine_scene, mesh, fine, o);
    dense_grid fine_grid(fine);
    appearance_walker<kernels::dense_grid_kernel> walker({fine_grid.blob().begin(), fine_grid.blob().end()},
                                                         fine_table, 1);
    voxel_model coarse = appearance::coarser_voxels(fine);
    structure = build_walk_structure(structure_name, coarse);
    method_table m{"ours_lod", {}, {}, 0};
    m.table = appearance::resample(walker, coarse, o, &m.stats);
    return m;
}

// A copy of `m` with precomputed shadows of `light`, walked over `s`; their time goes to
// the copy's shadow_us_per_voxel.
method_table with_shadows(const walk_structure& s, const method_table& m, const shading& light, unsigned threads) {
    method_table shadowed = m;
    appearance::precompute_stats stats;
    with_walk_kernel(s.name, [&]<class Kernel>() {
        appearance_walker<Kernel> walker(s.blob, m.table, threads);
        appearance::precompute_shadows(walker, shadowed.table, light.to_light, {.threads = threads}, &stats);
    });
    shadowed.shadow_us_per_voxel = stats.us_per_voxel();
    return shadowed;
}

// The walk of `rays` over `blob`; `seconds` gets the walk's time alone, without setting up
// the walker (copying the blob, building the ordinal index, starting its threads).
template <class Kernel>
std::vector<appearance_pixel> walk_rays(const std::vector<std::uint32_t>& blob, const method_table& m,
                                        const std::vector<ray>& rays, const shading& light, unsigned threads,
                                        double& seconds) {
    appearance_walker<Kernel> walker(blob, m.table, threads);
    auto start = std::chrono::steady_clock::now();
    std::vector<appearance_pixel> px = walker.walk(rays, {.to_light = light.to_light, .ambient = light.ambient});
    seconds = seconds_since(start);
    return px;
}

// Four rays a pixel (`rays`, pixel by pixel), blended over the background.
walked_picture walk_picture(const walk_structure& s, const method_table& m, const std::vector<ray>& rays,
                            const shading& light, int size, unsigned threads) {
    walked_picture w;
    std::vector<appearance_pixel> px = with_walk_kernel(s.name, [&]<class Kernel>() {
        return walk_rays<Kernel>(s.blob, m, rays, light, threads, w.seconds);
    });
    w.picture = blend_four(px, size, size, light.background);
    for (const appearance_pixel& p : px) w.steps += p.steps, w.visits += p.visits;
    w.steps /= double(px.size()), w.visits /= double(px.size());
    return w;
}

int appearance_bench(const appearance_bench_options& o) {
    const int size = o.size ? o.size : o.resolution;
    std::unique_ptr<output_file> out;
    if (!o.json.empty()) {
        out = std::make_unique<output_file>(o.json, "--json");
        nlohmann::json header = results_header(own_command_line(), 1);
        header["format"] = "voxray-appearance-bench-1";
        out->stream() << header.dump() << "\n";
    }
    if (!o.images.empty()) std::filesystem::create_directories(o.images);
    io::triangle_mesh mesh = gltf::load_coloured_mesh(o.mesh);
    voxel_model model = io::voxelize(mesh, {.resolution = o.resolution, .threads = o.threads});
    model.up_axis = 1;
    embree::triangle_scene scene(mesh, io::make_grid_map(mesh.bounds(), o.resolution));
    std::filesystem::path mesh_path(o.mesh);
    std::string folder = mesh_path.parent_path().filename().string();
    std::string scene_name = folder + "/" + mesh_path.filename().string();
    std::fprintf(stderr, "%s at %d: %llu voxels\n", scene_name.c_str(), o.resolution,
                 (unsigned long long)model.voxel_count());
    walk_structure structure = build_walk_structure(o.structure, model);

    // Averages, SGGX, faithful and ours do not depend on the light; six directions is made for each.
    method_table averages = precompute_method(scene, mesh, model, "averages", appearance::record_kind::averages, {},
                                              o.threads);
    method_table sggx = precompute_method(scene, mesh, model, "sggx", appearance::record_kind::sggx, {}, o.threads);
    method_table faithful =
        precompute_method(scene, mesh, model, "faithful", appearance::record_kind::faithful, {}, o.threads);
    method_table ours = precompute_method(scene, mesh, model, "ours", appearance::record_kind::compact, {}, o.threads);
    walk_structure lod_structure;
    std::optional<method_table> ours_lod;
    if (o.lod) ours_lod = resampled_method(mesh, o.resolution, o.structure, o.threads, lod_structure);
    std::printf("%-24s %4s %4s %-6s %-9s %9s %9s %7s %7s %7s %9s %9s\n", "scene", "res", "view", "light", "method",
                "mse", "mse fg", "psnr", "ssim", "B/voxel", "us/voxel", "walk fps");
    for (int view = 0; view < o.views; ++view) {
        camera cam = auto_camera(model.bounds(), model.up_axis, view * 8 / o.views);
        std::vector<shading> lights;
        for (bool front : {true, false})
            lights.push_back({light_direction(cam, front), 0.2f, glm::vec3(0.2f), o.shadows});
        auto reference = reference_pictures(scene, mesh, cam, size, size, o.reference_side, lights, o.threads);
        std::vector<ray> rays = four_rays_a_pixel(cam, size, size);
        for (std::size_t l = 0; l < lights.size(); ++l) {
            const char* light_name = l == 0 ? "front" : "behind";
            std::vector<std::uint8_t> ref8 = srgb8(reference[l]);
            std::vector<std::vector<std::uint8_t>> strip{ref8};  // reference | each method
            method_table six =
                precompute_method(scene, mesh, model, "six", appearance::record_kind::six, lights[l], o.threads);
            std::vector<const method_table*> methods{&averages, &sggx, &six, &faithful, &ours};  // the strip's order
            if (ours_lod) methods.push_back(&*ours_lod);
            for (const method_table* method : methods) {
                const bool lod = ours_lod && method == &*ours_lod;
                const walk_structure& walked = lod ? lod_structure : structure;
                const bool shadowed = o.shadows && method != &six;  // six is lit when made
                std::optional<method_table> with;
                if (shadowed) with = with_shadows(walked, *method, lights[l], o.threads);
                const method_table& m = with ? *with : *method;
                walked_picture w = walk_picture(walked, m, rays, lights[l], size, o.threads);
                std::vector<std::uint8_t> got8 = srgb8(w.picture);
                picture_errors e = compare(ref8, got8, reference[l].coverage, size, size);
                std::printf("%-24s %4d %4d %-6s %-9s %9.5f %9.5f %7.2f %7.4f %7.1f %9.1f %9.2f\n", scene_name.c_str(),
                            o.resolution, view, light_name, m.name.c_str(), e.mse, e.mse_foreground, e.psnr, e.ssim,
                            m.table.bytes_per_voxel(), m.stats.us_per_voxel(), 1.0 / w.seconds);
                std::fflush(stdout);
                if (out)
                    out->stream() << nlohmann::json{{"scene", scene_name}, {"resolution", o.resolution}, {"size", size},
                                                    {"lod_from", lod ? 2 * o.resolution : 0},
                                                    {"view", view}, {"light", light_name}, {"method", m.name},
                                                    {"shadows", shadowed},
                                                    {"shadow_us_per_voxel", m.shadow_us_per_voxel},
                                                    {"mse", e.mse}, {"mse_foreground", e.mse_foreground},
                                                    {"psnr", e.psnr}, {"ssim", e.ssim},
                                                    {"bytes_per_voxel", m.table.bytes_per_voxel()},
                                                    {"precompute_us_per_voxel", m.stats.us_per_voxel()},
                                                    {"precompute_rays_per_second", m.stats.rays_per_second()},
                                                    {"precompute_threads", o.threads},
                                                    {"voxels", m.table.voxels.size()},
                                                    {"reference_spp", o.reference_side * o.reference_side},
                                                    {"rays_per_pixel", 4}, {"walk_seconds", w.seconds},
                                                    {"walk_fps", 1.0 / w.seconds}, {"walk_threads", o.threads},
                                                    {"walk_structure", structure.name},
                                                    {"steps_per_ray", w.steps}, {"visits_per_ray", w.visits}}
                                         .dump()
                                  << "\n";
                strip.push_back(std::move(got8));
            }
            if (!o.images.empty())
                write_strip(strip, size, size,
                            (std::filesystem::path(o.images) / (folder + "_" + std::to_string(o.resolution) + "_view" +
                                                                 std::to_string(view) + "_" + light_name + ".png"))
                                .string());
        }
    }
    if (out) out->finish();
    return 0;
}

#else

int appearance_bench(const appearance_bench_options&) {
    fail("appearance-bench needs Embree (the precompute and the reference trace triangles): this build has none");
}

#endif

}  // namespace

command add_appearance_bench(CLI::App& parent) {
    auto* app = parent.add_subcommand("appearance-bench",
                                      "filtered voxel appearance against the triangles: quality, memory, time");
    auto o = std::make_shared<appearance_bench_options>();
    app->add_option("mesh", o->mesh, "a coloured mesh (.gltf, .glb, .obj, .ply)")->required()->check(CLI::ExistingFile);
    app->add_option("--resolution", o->resolution, "voxels along the mesh's longest axis")
        ->check(CLI::Range(8, 1024))->capture_default_str();
    app->add_option("--size", o->size, "picture side in pixels (0: the resolution)")
        ->check(CLI::Range(0, 4096))->capture_default_str();
    app->add_option("--views", o->views, "views around the mesh")->check(CLI::Range(1, 8))->capture_default_str();
    app->add_option("--reference-side", o->reference_side, "the reference's samples a pixel: side x side, stratified")
        ->check(CLI::Range(1, 64))->capture_default_str();
    app->add_option("--threads", o->threads, "threads of the precompute and the walk")
        ->check(CLI::Range(1u, 256u))->capture_default_str();
    app->add_option("--structure", o->structure, "the structure whose first-hit kernel the walk re-enters")
        ->check(CLI::IsMember(walk_structures))
        ->capture_default_str();
    app->add_flag("--shadows", o->shadows,
                  "cast shadows: in the reference, and precomputed for each light in every method but six");
    app->add_flag("--lod", o->lod,
                  "also ours_lod: ours re-sampled through the walk from ours at twice the resolution (a LOD level)");
    app->add_option("--json", o->json, "write one JSON line per method, view and light after a header line");
    app->add_option("--images", o->images,
                    "write each view's strip (reference | averages | sggx | six | faithful | ours [| ours_lod]) "
                    "here as PNG");
    return {app, [o] { return appearance_bench(*o); }};
}

}  // namespace voxray::tool
