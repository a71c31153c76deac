// voxray bench: Mrays/s of one structure x backend on primary, secondary (diffuse bounce)
// or shadow rays. One warm-up run, then --runs timed runs; every run's hits are validated
// against the dense grid on the CPU, and the machine-independent cost (steps per ray) is
// reported beside the times.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "args.hpp"
#include "edits.hpp"
#include "commands.hpp"
#include "engines.hpp"
#include "scene.hpp"
#include "voxray/check/compare.hpp"
#include "voxray/check/ray_sets.hpp"

namespace voxray::tool {


namespace {

// The CPU clock in Hz as the kernel reports it (the largest "cpu MHz" in /proc/cpuinfo),
// 0 when unknown. Cycles per ray-step = threads x clock / (rays/s x steps/ray).
double cpu_clock_hz() {
    std::ifstream in("/proc/cpuinfo");
    double best = 0;
    for (std::string line; std::getline(in, line);)
        if (line.rfind("cpu MHz", 0) == 0) {
            auto colon = line.find(':');
            if (colon != std::string::npos) best = std::max(best, std::atof(line.c_str() + colon + 1) * 1e6);
        }
    return best;
}

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

// The brickmap paper's editing load: 50 balls of radius 25 bouncing through the world;
// each frame erases every ball and fills it at its new place (100 sphere edits in one
// batch), then brings the backend up to date with only the changed words.
int run_edit_bench(const args& a, const voxel_model& model, const std::string& structure_name,
                   const std::string& backend) {
    std::string kind = a.get("edits", "");
    if (kind != "spheres" && kind != "voxel") fail("--edits must be 'spheres' or 'voxel', not '", kind, "'");
    unsigned threads = unsigned(a.number("threads", 2, 1, 256));
    int frames = int(a.number("runs", 20, 1, 100000));
    constexpr int balls = 50, radius = 25;

    auto structure = build_structure(structure_name, model);
    if (!structure->editable()) fail("--edits needs an editable structure, not ", structure_name);
    auto engine = structure->trace_on(backend);
    box3i world = model.bounds();
    rng g(11);
    std::vector<glm::vec3> position(balls), velocity(balls);
    glm::vec3 lo = glm::vec3(world.min), hi = glm::vec3(world.max);
    for (int i = 0; i < balls; ++i) {
        for (int k = 0; k < 3; ++k) {
            position[i][k] = g.uniform(lo[k], hi[k]);
            velocity[i][k] = g.uniform(-4.0f, 4.0f);
        }
    }
    auto sphere_at = [&](int i) { return regions::sphere{glm::ivec3(glm::floor(position[i])), radius}; };

    double edit_seconds = 0, update_seconds = 0;
    std::uint64_t writes = 0, uploaded = 0;
    std::vector<region_edit> edits;
    // Frame 0 is a warm-up, not counted: a map built to size grows its brick pool on its
    // first new brick, and that update sends the whole (reallocated) blob once.
    for (int f = 0; f <= frames; ++f) {
        std::fprintf(stderr, "frame %d/%d ...\r", f, frames);
        edits.clear();
        if (kind == "voxel") {  // the smallest edit: one voxel somewhere in the world
            glm::ivec3 e = world.extent();
            edits.push_back({regions::box{box3i{world.min + glm::ivec3(g.below(e.x), g.below(e.y), g.below(e.z)), {}}},
                             edit_op::fill, std::uint32_t(1 + g.below(255))});
            auto& b = std::get<regions::box>(edits.back().region).b;
            b.max = b.min + 1;
        }
        for (int i = 0; kind == "spheres" && i < balls; ++i) {
            edits.push_back({sphere_at(i), edit_op::erase, 0});
            for (int k = 0; k < 3; ++k) {  // bounce off the world's walls
                position[i][k] += velocity[i][k];
                if (position[i][k] < lo[k] || position[i][k] >= hi[k]) velocity[i][k] = -velocity[i][k];
                position[i][k] = std::clamp(position[i][k], lo[k], hi[k] - 1.0f);
            }
            edits.push_back({sphere_at(i), edit_op::fill, std::uint32_t(1 + i * 5)});
        }
        for (auto& e : edits) writes += f == 0 ? 0 : std::visit([&](const auto& r) { return region_voxels(r, world); }, e.region);
        if (f == 0) {
            structure->apply_edits(edits, threads);
            engine->after_edits(model);
            continue;
        }
        auto start = std::chrono::steady_clock::now();
        structure->apply_edits(edits, threads);  // edits, then takes the dirty ranges
        auto edited = std::chrono::steady_clock::now();
        engine->after_edits(model);
        auto synced = std::chrono::steady_clock::now();
        edit_seconds += std::chrono::duration<double>(edited - start).count();
        update_seconds += std::chrono::duration<double>(synced - edited).count();
        uploaded += engine->bytes_uploaded_last_update();
    }
    std::fprintf(stderr, "\n");
    double per_second = double(writes) / edit_seconds;
    double per_update = double(uploaded) / frames;
    std::printf("scene %s  structure %s  backend %s (%s)  %d frames of %s, %u threads\n",
                a.positional()[0].c_str(), structure_name.c_str(), backend.c_str(), engine->device().c_str(), frames,
                kind == "voxel" ? "one voxel edit" : "100 sphere edits (50 balls, r 25)", threads);
    std::printf("world %d x %d x %d, blob %zu bytes; %.2f ms edits and %.2f ms update per frame\n",
                world.extent().x, world.extent().y, world.extent().z, structure->bytes(), 1e3 * edit_seconds / frames,
                1e3 * update_seconds / frames);
    if (a.has("json")) {
        std::ofstream j(a.get("json", ""));
        j << "{\"scene\": \"" << a.positional()[0] << "\", \"structure\": \"" << structure_name << "\", \"backend\": \"" << backend
          << "\", \"edits\": \"" << kind << "\", \"threads\": " << threads << ", \"frames\": " << frames
          << ", \"voxel_writes\": " << writes << ", \"writes_per_second\": " << per_second
          << ", \"bytes_uploaded_per_update\": " << per_update << ", \"blob_bytes\": " << structure->bytes()
          << ", \"update_ms\": " << 1e3 * update_seconds / frames << "}\n";
        if (!j) fail("cannot write ", a.get("json", ""));
    }
    std::printf("edits: %.0f voxel writes/s, %.0f bytes uploaded per update\n", per_second, per_update);
    return 0;
}

}  // namespace

int run_bench(int argc, char** argv) {
    args a(argc, argv, 2,
           {"structure", "backend", "rays", "width", "height", "runs", "json", "resolution", "edits", "threads"});
    if (a.positional().size() != 1) fail("bench takes one SCENE");
    std::string scene = a.positional()[0], kind = a.get("rays", "primary");
    std::string structure_name = a.get("structure", "dense"), backend = a.get("backend", "cpu");
    int width = int(a.number("width", 1920, 1, 16384)), height = int(a.number("height", 1080, 1, 16384));
    int runs = int(a.number("runs", 5, 1, 1000));
    if (kind != "primary" && kind != "secondary" && kind != "shadow")
        fail("--rays must be primary, secondary or shadow, not '", kind, "'");
    auto model = load_scene(scene, int(a.number("resolution", 512, 1, 4096)));
    if (a.has("edits")) return run_edit_bench(a, model, structure_name, backend);

    std::fprintf(stderr, "building %s ...\n", structure_name.c_str());
    auto structure = build_structure(structure_name, model);
    auto engine = structure->trace_on(backend);
    auto reference_grid = structure_name == "dense" ? structure : build_structure("dense", model);
    auto reference = reference_grid->trace_on("cpu");

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
    std::printf("bytes %zu (%.2f per voxel)  build %.3f s  steps/ray %.2f\n", structure->bytes(),
                double(structure->bytes()) / double(std::max<std::uint64_t>(1, model.voxel_count())), structure->build_seconds(),
                steps);
    // A CPU backend's cost per step of one ray, from the measured clock (CPU backends with
    // steps only: a device's threads are not this machine's cores).
    double clock = cpu_clock_hz();
    unsigned threads = engine->cpu_threads();
    double cycles_per_step = threads > 0 && clock > 0 && steps > 0 ? threads * clock / (median * 1e6 * steps) : 0.0;
    if (cycles_per_step > 0)
        std::printf("cycles/ray-step %.1f (%u threads, %.2f GHz, %u lanes)\n", cycles_per_step, threads, clock * 1e-9,
                    engine->simd_width());
    std::printf("validated %zu rays x %d runs against dense/cpu: %llu mismatches, %llu ties\n", rays.size(), runs,
                (unsigned long long)mismatches, (unsigned long long)ties);
    if (a.has("json")) {
        std::ofstream j(a.get("json", ""));
        j << "{\"scene\": \"" << scene << "\", \"structure\": \"" << structure_name << "\", \"backend\": \"" << backend
          << "\", \"device\": \"" << engine->device() << "\", \"rays\": \"" << kind << "\", \"width\": " << width
          << ", \"height\": " << height << ", \"runs\": " << runs << ", \"ray_count\": " << rays.size()
          << ", \"voxels\": " << model.voxel_count() << ", \"bytes\": " << structure->bytes()
          << ", \"build_seconds\": " << structure->build_seconds() << ", \"steps_per_ray\": " << steps
          << ", \"cycles_per_ray_step\": " << cycles_per_step << ", \"threads\": " << threads
          << ", \"simd_width\": " << engine->simd_width() << ", \"clock_hz\": " << clock
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
