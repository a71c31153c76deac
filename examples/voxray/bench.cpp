// voxray bench: Mrays/s of one structure x backend on primary, secondary (diffuse bounce)
// or shadow rays. One warm-up run, then --runs timed runs; every run's hits are validated
// against the dense grid on the CPU, and the machine-independent cost (steps per ray) is
// reported beside the times.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>

#include "args.hpp"
#include "commands.hpp"
#include "engines.hpp"
#include "scene.hpp"
#include "voxray/check/compare.hpp"
#include "voxray/check/ray_sets.hpp"

namespace voxray::tool {


namespace {

// Rays of the requested kind; secondary and shadow rays start from the reference's hits.
std::vector<ray> make_rays(const std::string& kind, const voxel_model& model, traceable& reference, int w, int h) {
    auto primary = primary_rays(auto_camera(model.bounds(), model.up_axis, 0), w, h);
    if (kind == "primary") return primary;
    std::vector<hit> hits(primary.size());
    reference.closest_hit(primary, hits);
    if (kind == "secondary") return secondary_rays(primary, hits, 7);
    if (kind == "shadow") return shadow_rays(primary, hits, light_direction(model.up_axis));
    fail("--rays must be primary, secondary or shadow, not '", kind, "'");
}

}  // namespace

int run_bench(int argc, char** argv) {
    args a(argc, argv, 2, {"structure", "backend", "rays", "width", "height", "runs", "json", "resolution"});
    if (a.positional().size() != 1) fail("bench takes one SCENE");
    std::string scene = a.positional()[0], kind = a.get("rays", "primary");
    std::string structure_name = a.get("structure", "dense"), backend = a.get("backend", "cpu");
    int width = int(a.number("width", 1920, 1, 16384)), height = int(a.number("height", 1080, 1, 16384));
    int runs = int(a.number("runs", 5, 1, 1000));
    if (kind != "primary" && kind != "secondary" && kind != "shadow")
        fail("--rays must be primary, secondary or shadow, not '", kind, "'");
    auto model = load_scene(scene, int(a.number("resolution", 512, 1, 4096)));

    std::fprintf(stderr, "building %s ...\n", structure_name.c_str());
    auto structure = build_structure(structure_name, model);
    auto engine = make_traceable(structure, backend);
    auto reference_grid = structure_name == "dense" ? structure : build_structure("dense", model);
    auto reference = make_traceable(reference_grid, "cpu");

    auto rays = make_rays(kind, model, *reference, width, height);
    bool shadow = kind == "shadow";
    std::vector<hit> expected(rays.size()), hits(rays.size());
    auto trace = [&](traceable& t, std::vector<hit>& out) {
        if (shadow) t.any_hit(rays, out);
        else t.closest_hit(rays, out);
    };
    trace(*reference, expected);

    std::fprintf(stderr, "warm-up on %s ...\n", engine->device().c_str());
    trace(*engine, hits);
    std::vector<double> mrays;
    std::uint64_t mismatches = 0, ties = 0;
    for (int r = 0; r < runs; ++r) {
        std::fprintf(stderr, "run %d/%d ...\r", r + 1, runs);
        std::fill(hits.begin(), hits.end(), hit{});
        auto start = std::chrono::steady_clock::now();
        trace(*engine, hits);
        double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        mrays.push_back(double(rays.size()) / s * 1e-6);
        for (std::size_t i = 0; i < rays.size(); ++i) {
            // Any-hit answers may name different voxels: only whether one exists must agree.
            auto verdict = shadow ? (hits[i].is_hit() == expected[i].is_hit() ? agreement::same : agreement::mismatch)
                                  : compare_hits(rays[i], expected[i], hits[i]);
            mismatches += verdict == agreement::mismatch;
            ties += verdict == agreement::tie;
        }
    }
    std::fprintf(stderr, "\n");
    double steps = 0;
    for (auto& h : hits) steps += h.steps;
    steps /= double(std::max<std::size_t>(1, hits.size()));
    std::vector<double> sorted = mrays;
    std::sort(sorted.begin(), sorted.end());
    double median = sorted[sorted.size() / 2], lo = sorted.front(), hi = sorted.back();

    std::printf("scene %s  structure %s  backend %s (%s)  rays %s %dx%d  runs %d\n", scene.c_str(),
                structure_name.c_str(), backend.c_str(), engine->device().c_str(), kind.c_str(), width, height, runs);
    std::printf("bytes %zu (%.2f per voxel)  build %.3f s  steps/ray %.2f\n", structure.bytes,
                double(structure.bytes) / double(std::max<std::uint64_t>(1, model.voxel_count())), structure.build_seconds,
                steps);
    std::printf("validated %zu rays x %d runs against dense/cpu: %llu mismatches, %llu ties\n", rays.size(), runs,
                (unsigned long long)mismatches, (unsigned long long)ties);
    if (a.has("json")) {
        std::ofstream j(a.get("json", ""));
        j << "{\"scene\": \"" << scene << "\", \"structure\": \"" << structure_name << "\", \"backend\": \"" << backend
          << "\", \"device\": \"" << engine->device() << "\", \"rays\": \"" << kind << "\", \"width\": " << width
          << ", \"height\": " << height << ", \"runs\": " << runs << ", \"ray_count\": " << rays.size()
          << ", \"voxels\": " << model.voxel_count() << ", \"bytes\": " << structure.bytes
          << ", \"build_seconds\": " << structure.build_seconds << ", \"steps_per_ray\": " << steps
          << ", \"mrays_median\": " << median << ", \"mrays_min\": " << lo << ", \"mrays_max\": " << hi
          << ", \"mrays_runs\": [";
        for (std::size_t i = 0; i < mrays.size(); ++i) j << (i ? ", " : "") << mrays[i];
        j << "], \"mismatches\": " << mismatches << ", \"ties\": " << ties << "}\n";
        if (!j) fail("cannot write ", a.get("json", ""));
    }
    std::printf("median %.2f Mrays/s (min %.2f, max %.2f)\n", median, lo, hi);
    return mismatches == 0 ? 0 : 1;
}

}  // namespace voxray::tool
