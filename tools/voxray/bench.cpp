// voxray bench: the benchmark matrix, structures x backends x scenes x ray sets in one run.
// Per row: warm-up runs, then the median (min, max) of --runs timed runs; every timed run's
// hits are validated against the reference (dense grid on the CPU) while measuring. A row
// that disagrees or fails is reported and the matrix goes on; a baseline's known limitation
// (Embree quads cannot answer rays that start inside solid) is labelled, its rays counted
// apart. Results: one JSON line per row after a header line (--out); see README.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>

#include <nlohmann/json.hpp>

#include "bench_header.hpp"
#include "bench_options.hpp"
#include "cli.hpp"
#include "engines.hpp"
#include "entity_scene.hpp"
#include "output.hpp"
#include "voxray/check/compare.hpp"
#include "voxray/check/ray_sets.hpp"
#include "voxray/io/ray_file.hpp"

namespace voxray::tool {

namespace {

struct ray_set {
    std::string name;
    std::vector<ray> rays;
    std::vector<hit> expected;  // the reference's answers
    bool shadow = false;        // any-hit (only whether something is hit must agree)
    int width = 0, height = 0;  // 0 for a ray file
};

// `text` with ':' (builtin:menger:81) made '_', usable as a file name anywhere.
std::string file_name(std::string text) {
    std::replace(text.begin(), text.end(), ':', '_');
    return text;
}

// The ray sets of one scene, with the reference's answers. Secondary and shadow rays start
// from the reference's primary hits, so every structure gets the very same rays.
std::vector<ray_set> make_ray_sets(const bench_options& o, const voxel_model& model, traceable& reference,
                                   const std::vector<ray>& file_rays) {
    std::vector<ray_set> sets;
    auto primary = primary_rays(auto_camera(model.bounds(), model.up_axis, 0), o.width, o.height,
                                o.pixel_order == "rows" ? pixel_order::rows : pixel_order::tiles);
    std::vector<hit> primary_hits(primary.size());
    reference.closest_hit(primary, primary_hits);
    for (auto& name : split_names(o.ray_sets)) {
        ray_set s{name, {}, {}, name == "shadow", o.width, o.height};
        if (name == "primary") s.rays = primary;
        if (name == "secondary") s.rays = diffuse_rays(primary, primary_hits, 7);
        if (name == "shadow") s.rays = shadow_rays(primary, primary_hits, sun_direction(model.up_axis));
        sets.push_back(std::move(s));
    }
    if (!o.ray_file.empty()) sets.push_back({"file:" + std::filesystem::path(o.ray_file).stem().string(), file_rays, {}, false, 0, 0});
    for (auto& s : sets) {
        s.expected.resize(s.rays.size());
        if (s.shadow) reference.any_hit(s.rays, s.expected);
        else reference.closest_hit(s.rays, s.expected);
    }
    return sets;
}

// Whether ray r starts inside a solid voxel of the model.
bool starts_inside_solid(const ray& r, const voxel_model& model) {
    glm::vec3 p = r.origin + r.direction * r.tmin;
    if (!(std::abs(p.x) < 1e9f && std::abs(p.y) < 1e9f && std::abs(p.z) < 1e9f)) return false;
    return model.get(glm::ivec3(glm::floor(p))) != 0;
}

// Any-hit answers carry only a status. Where the reference's says "hit" and the other's
// "miss", the reference's closest hit tells whether that is a graze or a touch at tmax,
// which compare_hits() counts as a tie.
agreement judge_any_hit(const ray& r, const hit& expected, const hit& got, traceable& reference) {
    if (expected.is_hit() == got.is_hit()) return agreement::same;
    if (!expected.is_hit()) return agreement::mismatch;
    std::vector<ray> one{r};
    std::vector<hit> closest(1);
    reference.closest_hit(one, closest);
    return compare_hits(r, closest[0], hit{});
}

// The median of a non-empty list.
double median_of(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Times one structure x backend on one ray set and validates every timed run.
nlohmann::json measure(const bench_options& o, slot& structure, traceable& engine, const ray_set& set,
                       const voxel_model& model, traceable& reference) {
    std::vector<hit> hits(set.rays.size());
    auto trace = [&] {
        if (set.shadow) engine.any_hit(set.rays, hits);
        else engine.closest_hit(set.rays, hits);
    };
    for (int w = 0; w < o.warmup; ++w) trace();
    std::string limitation = structure.limitation();
    auto colours = structure.colour_tolerance();  // hits with colours: within it of the palette's
    std::vector<double> mrays, kernel_mrays;  // whole trace; the device's kernels alone (GPU backends)
    std::uint64_t mismatches = 0, ties = 0, limited = 0;
    for (int r = 0; r < o.runs; ++r) {
        std::fill(hits.begin(), hits.end(), hit{});
        auto start = std::chrono::steady_clock::now();
        trace();
        double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        mrays.push_back(double(set.rays.size()) / s * 1e-6);
        double kernel_s = engine.kernel_seconds_last_trace();
        if (std::isfinite(kernel_s) && kernel_s > 0) kernel_mrays.push_back(double(set.rays.size()) / kernel_s * 1e-6);
        for (std::size_t i = 0; i < set.rays.size(); ++i) {
            auto verdict = set.shadow ? judge_any_hit(set.rays[i], set.expected[i], hits[i], reference)
                           : colours ? compare_colour_hits(set.rays[i], set.expected[i], hits[i], model.palette(), *colours)
                                     : compare_hits(set.rays[i], set.expected[i], hits[i]);
            if (verdict == agreement::mismatch && !limitation.empty() && starts_inside_solid(set.rays[i], model)) ++limited;
            else mismatches += verdict == agreement::mismatch;
            ties += verdict == agreement::tie;
        }
    }
    double steps = 0;
    for (auto& h : hits) steps += h.steps;
    steps /= double(std::max<std::size_t>(1, hits.size()));
    std::vector<double> sorted = mrays;
    std::sort(sorted.begin(), sorted.end());
    double median = median_of(mrays);
    double clock = cpu_clock_hz();
    unsigned threads = engine.cpu_threads();
    // A CPU backend's cost per step of one ray (a device's threads are not this machine's cores).
    double cycles = threads > 0 && clock > 0 && steps > 0 ? threads * clock / (median * 1e6 * steps) : NAN;
    std::uint64_t voxels = model.voxel_count();
    nlohmann::json figures = nlohmann::json::object();
    for (auto& [name, value] : structure.figures()) figures[name] = value;
    return {{"steps_per_ray", steps},
            {"cycles_per_ray_step", cycles},
            {"threads", threads},
            {"simd_width", engine.simd_width()},
            {"work_group_size", engine.work_group_size()},
            {"mrays_median", median},
            {"mrays_min", sorted.front()},
            {"mrays_max", sorted.back()},
            {"mrays_runs", mrays},
            // Without the copies of rays and hits between host and device: what the kernel
            // would trace on rays made and used on the device (null: not measured).
            {"kernel_mrays_median", kernel_mrays.size() == mrays.size() ? median_of(kernel_mrays) : NAN},
            {"bytes", structure.bytes()},
            {"bytes_per_voxel", voxels ? double(structure.bytes()) / double(voxels) : NAN},
            {"build_seconds", structure.build_seconds()},
            {"figures", figures},
            {"validated_rays", set.rays.size() * std::size_t(o.runs)},
            {"mismatches", mismatches},
            {"ties", ties},
            {"limitation", limitation.empty() ? nlohmann::json() : nlohmann::json(limitation)},
            {"limitation_rays", limited}};
}

void print_row(const nlohmann::json& r) {
    if (r.contains("error")) {
        std::printf("%-22s %-14s %-11s %-10s  error: %s\n", r["scene"].get<std::string>().c_str(),
                    r["structure"].get<std::string>().c_str(), r["backend"].get<std::string>().c_str(),
                    r["ray_set"].get<std::string>().c_str(), r["error"].get<std::string>().c_str());
        return;
    }
    auto limited = r["limitation_rays"].get<std::uint64_t>();
    std::string label = limited ? "  (+" + std::to_string(limited) + " labelled: " + r["limitation"].get<std::string>() + ")" : "";
    // A device's kernels alone, beside the whole trace (NaN where the backend has no kernel timing).
    if (r["kernel_mrays_median"].is_number() && std::isfinite(r["kernel_mrays_median"].get<double>()))
        label += "  (kernel " + std::to_string(std::lround(r["kernel_mrays_median"].get<double>())) + " Mrays/s)";
    std::printf("%-22s %-14s %-11s %-10s %9.2f %9.2f %9.2f %9.2f %9.2f %10llu%s\n", r["scene"].get<std::string>().c_str(),
                r["structure"].get<std::string>().c_str(), r["backend"].get<std::string>().c_str(),
                r["ray_set"].get<std::string>().c_str(), r["mrays_median"].get<double>(), r["mrays_min"].get<double>(),
                r["mrays_max"].get<double>(), r["steps_per_ray"].get<double>(),
                r["bytes_per_voxel"].is_number() ? r["bytes_per_voxel"].get<double>() : 0.0,
                (unsigned long long)r["mismatches"].get<std::uint64_t>(),
                label.c_str());
    std::fflush(stdout);
}

}  // namespace

int run_matrix(const bench_options& o) {
    auto structures = split_names(o.structures), backends = split_names(o.backends);
    auto sets_per_scene = split_names(o.ray_sets).size() + (o.ray_file.empty() ? 0 : 1);
    // Rays, reference hits and hits under test, per ray set of one scene.
    require_memory(std::uint64_t(o.width) * std::uint64_t(o.height) * (sizeof(ray) + 3 * sizeof(hit)) * (sets_per_scene + 1),
                   "bench at " + std::to_string(o.width) + " x " + std::to_string(o.height));
    if (!o.out.empty()) require_writable(o.out, "--out");
    if (!o.write_rays.empty()) {
        require_writable_folder(o.write_rays, "--write-rays");
        // Scenes of one file name would write the same ray files: refused, not overwritten.
        std::map<std::string, std::string> writer;
        for (auto& spec : o.scene.scenes) {
            auto [it, fresh] = writer.emplace(file_name(scene_label(spec)), spec);
            if (!fresh && it->second != spec)
                fail("--write-rays ", o.write_rays, ": scenes ", it->second, " and ", spec, " would both write ", it->first,
                     ".*.vxrays; write their rays in two runs");
        }
    }
    // A ray file is read once, after its header and the memory its rays take (with their
    // hits, and a copy per scene's ray sets) are checked; a bad one fails now.
    std::vector<ray> file_rays;
    if (!o.ray_file.empty()) {
        std::uint64_t count = io::ray_file_count(o.ray_file);
        require_memory(count * (2 * sizeof(ray) + 3 * sizeof(hit)), "--ray-file " + o.ray_file + " (" + std::to_string(count) + " rays)");
        file_rays = io::read_rays(o.ray_file);
    }

    std::optional<output_file> out;
    if (!o.out.empty()) {
        out.emplace(o.out, "--out");
        out->stream() << results_header(own_command_line(), build_structure("dense", voxel_model{})->trace_on("cpu")->simd_width()).dump() << "\n";
    }
    std::printf("%-22s %-14s %-11s %-10s %9s %9s %9s %9s %9s %10s\n", "scene", "structure", "backend", "rays", "Mrays/s",
                "min", "max", "steps/ray", "B/voxel", "mismatches");
    std::size_t rows = 0, total = o.scene.scenes.size() * structures.size() * backends.size() * sets_per_scene;
    int failed = 0, emitted = 0;
    auto emit = [&](nlohmann::json row) {
        print_row(row);
        ++emitted;
        if (out) out->stream() << row.dump() << "\n" << std::flush;
        failed += row.contains("error") || row.value("mismatches", std::uint64_t(0)) > 0;
    };
    for (auto& spec : o.scene.scenes) {
        voxel_model model;
        std::shared_ptr<slot> reference;
        std::unique_ptr<traceable> reference_engine;
        std::vector<ray_set> sets;
        try {  // a scene that cannot be loaded is one error row; the other scenes still run
            model = load_scene(spec, o.scene);
            reference = build_structure("dense", model);
            std::fprintf(stderr, "tracing the reference (dense, cpu) for the ray sets ...\n");
            reference_engine = reference->trace_on("cpu");
            sets = make_ray_sets(o, model, *reference_engine, file_rays);
        } catch (const std::exception& e) {
            emit({{"type", "row"}, {"scene", scene_label(spec)}, {"voxels", 0}, {"structure", "*"}, {"backend", "*"},
                  {"ray_set", "*"}, {"error", e.what()}});
            continue;
        }
        for (auto& s : sets)
            if (!o.write_rays.empty() && s.width)
                io::write_rays(std::filesystem::path(o.write_rays) / file_name(scene_label(spec) + "." + s.name + ".vxrays"), s.rays);
        for (auto& name : structures) {
            std::shared_ptr<slot> structure;
            std::string build_error;
            std::fprintf(stderr, "building %s ...\n", name.c_str());
            try {
                structure = name == "dense" ? reference : build_structure(name, model);
            } catch (const std::exception& e) {
                build_error = e.what();
            }
            for (auto& backend : backends) {
                if (structure && !structure->runs_on(backend)) {
                    rows += sets.size();
                    continue;  // e.g. Embree on opencl: the pair does not exist
                }
                std::unique_ptr<traceable> engine;
                std::string error = build_error;
                try {
                    if (structure) engine = structure->trace_on(backend);
                } catch (const std::exception& e) {
                    error = e.what();
                }
                for (auto& set : sets) {
                    std::fprintf(stderr, "[%zu/<=%zu] %s / %s / %s / %s ...\n", ++rows, total, scene_label(spec).c_str(),
                                 name.c_str(), backend.c_str(), set.name.c_str());
                    nlohmann::json row = {{"type", "row"}, {"scene", scene_label(spec)}, {"voxels", model.voxel_count()},
                                          {"structure", name}, {"backend", backend},
                                          {"device", engine ? engine->device() : std::string()}, {"ray_set", set.name},
                                          {"width", set.width}, {"height", set.height}, {"rays", set.rays.size()},
                                          {"pixel_order", set.width ? o.pixel_order : std::string()},
                                          {"runs", o.runs}, {"warmup", o.warmup}};
                    try {
                        if (!engine) fail(error);
                        row.update(measure(o, *structure, *engine, set, model, *reference_engine));
                    } catch (const std::exception& e) {
                        row["error"] = e.what();
                    }
                    emit(row);
                }
            }
        }
    }
    if (out) out->finish();
    std::printf("%d rows; %d with mismatches or errors%s\n", emitted, failed, o.out.empty() ? "" : ("; results in " + o.out).c_str());
    return failed == 0 ? 0 : 1;
}

command add_bench(CLI::App& parent) {
    auto* app = parent.add_subcommand("bench", "benchmark matrix: structures x backends x scenes x ray sets, validated; "
                                               "or --edits: the brickmap's editing rates");
    auto o = std::make_shared<bench_options>();
    o->structures = structure_names(",");  // every registered structure and baseline
    o->backends = join_names(backend_names());
    o->ray_sets = "primary,secondary,shadow";
    o->scene.add_to(app, true);
    app->add_option("--structures,--structure", o->structures, "structures (and baselines) to measure")
        ->check(names_from(all_structure_names(), "structure"))->capture_default_str();
    app->add_option("--backends,--backend", o->backends, "backends to measure on")
        ->check(names_from(backend_names(), "backend"))->capture_default_str();
    app->add_option("--rays", o->ray_sets, "ray sets: primary (camera at W x H), secondary (diffuse bounces), shadow")
        ->check(names_from(ray_set_names, "ray set"))->capture_default_str();
    app->add_option("--ray-file", o->ray_file, "also trace the rays of this .vxrays file (closest hit)")->check(CLI::ExistingFile);
    app->add_option("--write-rays", o->write_rays, "write each generated ray set to DIR/SCENE.SET.vxrays");
    app->add_option("--width", o->width, "primary ray columns")->check(CLI::Range(1, 16384))->capture_default_str();
    app->add_option("--height", o->height, "primary ray rows")->check(CLI::Range(1, 16384))->capture_default_str();
    app->add_option("--pixel-order", o->pixel_order,
                    "order of the primary rays (and so of the secondary and shadow rays made from them): rows, or "
                    "8x8 tiles in Z order")
        ->check(CLI::IsMember({"rows", "tiles"}))->capture_default_str();
    app->add_option("--runs", o->runs, "timed runs (median reported); frames with --edits")->check(CLI::Range(1, 100000))->capture_default_str();
    app->add_option("--warmup", o->warmup, "untimed runs first")->check(CLI::Range(0, 100))->capture_default_str();
    app->add_option("--out,--json", o->out, "results file: a header line, then one JSON line per row");
    app->add_option("--edits", o->edits, "measure editing instead: spheres (50 balls a frame) or voxel")
        ->check(CLI::IsMember({"spheres", "voxel"}));
    app->add_option("--threads", o->threads, "threads that apply edits")->check(CLI::Range(1u, 256u))->capture_default_str();
    o->candidates = all_candidates();
    app->add_option("--candidates", o->candidates, "a scene file's ways to find candidate entities, each measured")
        ->check(names_from(candidates_names(), "way"))->capture_default_str();
    return {app, [o, app] {
        if (!o->scene.scenes.empty() && is_scene_description(o->scene.scenes[0])) return bench_scene_file(*o);
        if (o->edits.empty()) return run_matrix(*o);
        bench_options edit = *o;  // editing defaults: the editable brickmap on the CPU
        if (!app->count("--structures")) edit.structures = "brickmap";
        if (!app->count("--backends")) edit.backends = "cpu";
        if (!app->count("--runs")) edit.runs = 20;
        return run_edit_bench(edit);
    }};
}

}  // namespace voxray::tool
