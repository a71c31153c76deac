// voxray appearance-walk-bench: how fast the compositing walk draws (issue 25's render
// target: 256^2 pixels x 4 rays at 256^3 on 2 threads, at least 27 frames a second). For one
// mesh at one resolution: the averages and ours (compact) tables precomputed once, then for
// each structure whose first-hit kernel the walk re-enters (dense, brickmap, naadf) and each
// CPU backend (cpu: the closest hits on SIMD lanes, in rounds; cpu-scalar: one ray at a time)
// the walk of one view's rays, --runs times, beside the first-hit kernel's own rate on the
// same rays. One JSON line per structure, backend and method after a header line: frames a
// second (median and the runs), nanoseconds and cycles a ray per thread, steps and voxels
// visited a ray, and the first hit's Mrays/s, steps a ray and cycles a ray-step.
#include <chrono>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "bench_header.hpp"
#include "cli.hpp"
#include "engines.hpp"
#include "output.hpp"
#include "timing.hpp"
#include "voxray/rays/camera.hpp"

#if VOXRAY_WITH_EMBREE
#include "appearance_pictures.hpp"
#include "appearance_structures.hpp"
#include "voxray/appearance/precompute.hpp"
#include "voxray/cpu/appearance_walk.hpp"
#include "voxray/embree/triangle_scene.hpp"
#include "voxray/gltf/coloured_mesh.hpp"
#endif

namespace voxray::tool {

namespace {

struct appearance_walk_bench_options {
    std::string mesh;
    int resolution = 256;
    int size = 0;  // picture side in pixels; 0: the resolution
    int view = 0;
    unsigned threads = 2;
    int runs = 5;
    std::string structures = join_names(walk_structures);
    std::string backends = join_names(walk_backends);
    std::string json;
};

#if VOXRAY_WITH_EMBREE

// The walk's figures on one structure and backend.
struct walk_timing {
    std::vector<double> fps;  // a frame = every ray once
    double steps = 0, visits = 0;  // means a ray
    unsigned simd_width = 1;
};

template <class Kernel, class Backend>
walk_timing time_walk(const walk_structure& s, const appearance::appearance_table& table, const std::vector<ray>& rays,
                      const appearance_light& light, const appearance_walk_bench_options& o) {
    appearance_walker<Kernel, Backend> walker(s.blob, table, o.threads);
    walk_timing t;
    t.simd_width = walker.simd_width();
    walker.walk(rays, light);  // warm-up: caches, the pool's threads
    for (int r = 0; r < o.runs; ++r) {
        auto start = std::chrono::steady_clock::now();
        std::vector<appearance_pixel> px = walker.walk(rays, light);
        t.fps.push_back(1.0 / seconds_since(start));
        if (r > 0) continue;
        for (const appearance_pixel& p : px) t.steps += p.steps, t.visits += p.visits;
        t.steps /= double(px.size()), t.visits /= double(px.size());
    }
    return t;
}

// The first-hit kernel's closest hits of the same rays on the tool's cpu backend: Mrays/s
// (median of o.runs) and steps a ray.
std::pair<double, double> time_first_hit(const std::string& structure, const voxel_model& model,
                                         const std::vector<ray>& rays, int runs) {
    std::unique_ptr<traceable> engine = build_structure(structure, model)->trace_on(cpu::name);
    std::vector<hit> hits(rays.size());
    engine->closest_hit(rays, hits);  // warm-up
    std::vector<double> mrays;
    for (int r = 0; r < runs; ++r) {
        auto start = std::chrono::steady_clock::now();
        engine->closest_hit(rays, hits);
        mrays.push_back(double(rays.size()) / seconds_since(start) * 1e-6);
    }
    double steps = 0;
    for (const hit& h : hits) steps += h.steps;
    return {percentile(mrays, 0.5), steps / double(rays.size())};
}

int appearance_walk_bench(const appearance_walk_bench_options& o) {
    const int size = o.size ? o.size : o.resolution;
    std::unique_ptr<output_file> out;
    if (!o.json.empty()) {
        out = std::make_unique<output_file>(o.json, "--json");
        nlohmann::json header = results_header(own_command_line(), 1);
        header["format"] = "voxray-appearance-walk-bench-1";
        out->stream() << header.dump() << "\n";
    }
    io::triangle_mesh mesh = gltf::load_coloured_mesh(o.mesh);
    voxel_model model = io::voxelize(mesh, {.resolution = o.resolution, .threads = o.threads});
    model.up_axis = 1;
    embree::triangle_scene scene(mesh, io::make_grid_map(mesh.bounds(), o.resolution));
    std::filesystem::path mesh_path(o.mesh);
    const std::string scene_name = mesh_path.parent_path().filename().string() + "/" + mesh_path.filename().string();
    std::fprintf(stderr, "%s at %d: %llu voxels\n", scene_name.c_str(), o.resolution,
                 (unsigned long long)model.voxel_count());
    // The tables, timed: through each voxel's own triangles (the precompute's way), and ours
    // again with every ray descending Embree's BVH from the root, the peer of that way.
    std::vector<std::pair<std::string, appearance::appearance_table>> tables;
    std::printf("%-24s %4s %-9s %-16s %9s %10s %12s %10s\n", "scene", "res", "method", "rays meet", "seconds",
                "us/voxel", "us/vox/thread", "Mrays/s");
    auto time_precompute = [&](const char* method, appearance::record_kind kind, bool voxel_lists) {
        appearance::precompute_stats stats;
        appearance::appearance_table table = appearance::precompute(
            scene, mesh, model, {.kind = kind, .threads = o.threads, .voxel_lists = voxel_lists}, &stats);
        const char* path = voxel_lists ? "voxel_lists" : "embree_bvh";
        std::printf("%-24s %4d %-9s %-16s %9.2f %10.2f %12.2f %10.2f\n", scene_name.c_str(), o.resolution, method, path,
                    stats.seconds, stats.us_per_voxel(), stats.us_per_voxel() * o.threads,
                    stats.rays_per_second() * 1e-6);
        if (out)
            out->stream() << nlohmann::json{{"row", "precompute"}, {"scene", scene_name}, {"resolution", o.resolution},
                                            {"voxels", stats.voxels}, {"method", method}, {"rays_meet", path},
                                            {"threads", o.threads}, {"seconds", stats.seconds},
                                            {"us_per_voxel", stats.us_per_voxel()}, {"rays", stats.rays},
                                            {"rays_per_second", stats.rays_per_second()}}
                                 .dump()
                          << "\n";
        return table;
    };
    for (auto [name, kind] : {std::pair{"averages", appearance::record_kind::averages},
                              {"ours", appearance::record_kind::compact}})
        tables.emplace_back(name, time_precompute(name, kind, true));
    time_precompute("ours", appearance::record_kind::compact, false);
    camera cam = auto_camera(model.bounds(), model.up_axis, o.view);
    const std::vector<ray> rays = four_rays_a_pixel(cam, size, size);
    const appearance_light light{.to_light = light_direction(cam, true), .ambient = 0.2f};
    const double clock = cpu_clock_hz();
    std::printf("%-24s %4s %-9s %-10s %4s %-9s %8s %9s %9s %7s %7s %12s %11s\n", "scene", "res", "structure",
                "backend", "simd", "method", "walk fps", "ns/ray", "cycles", "steps", "visits", "1st-hit Mr/s",
                "1st steps");
    for (const std::string& structure_name : split_names(o.structures)) {
        walk_structure structure = build_walk_structure(structure_name, model);
        auto [first_mrays, first_steps] = time_first_hit(structure_name, model, rays, o.runs);
        for (const std::string& backend : split_names(o.backends)) {
            for (const auto& [method, table] : tables) {
                walk_timing t = with_walk_kernel(structure_name, [&]<class Kernel>() {
                    return with_walk_backend(backend, [&]<class Backend>() {
                        return time_walk<Kernel, Backend>(structure, table, rays, light, o);
                    });
                });
                const double fps = percentile(t.fps, 0.5);
                const double ns = 1e9 * double(o.threads) / (fps * double(rays.size()));  // per ray and thread
                const double cycles = ns * 1e-9 * clock;
                std::printf("%-24s %4d %-9s %-10s %4u %-9s %8.2f %9.1f %9.0f %7.1f %7.2f %12.1f %11.1f\n",
                            scene_name.c_str(), o.resolution, structure_name.c_str(), backend.c_str(), t.simd_width,
                            method.c_str(), fps, ns, cycles, t.steps, t.visits, first_mrays, first_steps);
                std::fflush(stdout);
                if (out)
                    out->stream() << nlohmann::json{{"row", "walk"}, {"scene", scene_name},
                                                    {"resolution", o.resolution},
                                                    {"size", size}, {"rays_per_pixel", 4}, {"view", o.view},
                                                    {"voxels", model.voxel_count()}, {"structure", structure_name},
                                                    {"backend", backend}, {"simd_width", t.simd_width},
                                                    {"method", method}, {"threads", o.threads},
                                                    {"walk_fps", fps}, {"walk_fps_runs", t.fps},
                                                    {"ns_per_ray_thread", ns}, {"cycles_per_ray", cycles},
                                                    {"steps_per_ray", t.steps}, {"visits_per_ray", t.visits},
                                                    {"first_hit_mrays", first_mrays},
                                                    {"first_hit_steps_per_ray", first_steps},
                                                    {"first_hit_cycles_per_ray_step",
                                                     double(o.threads) * clock / (first_mrays * 1e6 * first_steps)}}
                                         .dump()
                                  << "\n";
            }
        }
    }
    if (out) out->finish();
    return 0;
}

#else

int appearance_walk_bench(const appearance_walk_bench_options&) {
    fail("appearance-walk-bench needs Embree (the tables are precomputed from the triangles): this build has none");
}

#endif

}  // namespace

command add_appearance_walk_bench(CLI::App& parent) {
    auto* app = parent.add_subcommand("appearance-walk-bench",
                                      "the compositing walk's speed on each structure and CPU backend");
    auto o = std::make_shared<appearance_walk_bench_options>();
    app->add_option("mesh", o->mesh, "a coloured mesh (.gltf, .glb, .obj, .ply)")->required()->check(CLI::ExistingFile);
    app->add_option("--resolution", o->resolution, "voxels along the mesh's longest axis")
        ->check(CLI::Range(8, 1024))->capture_default_str();
    app->add_option("--size", o->size, "picture side in pixels, 4 rays each (0: the resolution)")
        ->check(CLI::Range(0, 4096))->capture_default_str();
    app->add_option("--view", o->view, "the view around the mesh (appearance-bench's numbering)")
        ->check(CLI::Range(0, 7))->capture_default_str();
    app->add_option("--threads", o->threads, "threads of the precompute and the walk")
        ->check(CLI::Range(1u, 256u))->capture_default_str();
    app->add_option("--runs", o->runs, "timed walks of each (their median is reported)")
        ->check(CLI::Range(1, 100))->capture_default_str();
    app->add_option("--structures", o->structures, "structures whose first-hit kernels the walk re-enters")
        ->check(names_from(walk_structures, "structure"))->capture_default_str();
    app->add_option("--backends", o->backends, "CPU backends the walk runs on")
        ->check(names_from(walk_backends, "backend"))->capture_default_str();
    app->add_option("--json", o->json, "write one JSON line per structure, backend and method after a header line");
    return {app, [o] { return appearance_walk_bench(*o); }};
}

}  // namespace voxray::tool
