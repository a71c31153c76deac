// voxray bench SCENE.json: scenes with entities, per world kind x backend x ray set, on the
// same rays (the world's auto camera, 0) in three placements of the same instances:
//   none       the world's own tracer, no scene: what entities cost is measured against it;
//   off-paths  every instance moved behind the camera, where no primary ray goes: the cost
//              of entities a ray does not meet (the BVH's root box test);
//   in-view    the scene at frame 0, as the file places it;
// the scene rows once per way of finding candidate instances (--candidates: the BVH, the
// chunk lists), plus Embree's instancing peer (embree-instances: world quads, a quad scene
// per model, instances by transform) on the CPU in the same run, and per world kind x
// backend x way one "update" row: --runs frames of the file's motion, every instance
// moving, the host seconds of scene.move + tracer.update and the bytes sent. Rows are JSON
// lines after a header (--out), like the matrix's, with `entities`, `placement` and
// `candidates` in each.
//
// Validation: every timed run's hits are compared with the brute-force reference
// (entities/reference.hpp) where rays x instances stay below 4e8 (it walks every instance
// for every ray), else with the cpu-scalar scene; Embree's rows count disagreements of hit
// status (its float quads are a speed peer, see embree/instanced_scene.hpp).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>

#include <nlohmann/json.hpp>

#include "backends.hpp"
#include "bench_header.hpp"
#include "bench_options.hpp"
#include "cli.hpp"
#include "engines.hpp"
#include "entity_scene.hpp"
#include "output.hpp"
#include "voxray/entities/scene_hit.hpp"
#include "voxray/rays.hpp"
#if VOXRAY_WITH_EMBREE
#include "voxray/embree/instanced_scene.hpp"
#endif

namespace voxray::tool {

namespace {

using json = nlohmann::json;

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    std::size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Times `trace` (which fills hits) over warm-up and runs; Mrays/s median, min, max.
template <class F>
json time_runs(const bench_options& o, std::size_t rays, F&& trace) {
    for (int w = 0; w < o.warmup; ++w) trace();
    std::vector<double> mrays;
    for (int r = 0; r < o.runs; ++r) {
        auto start = std::chrono::steady_clock::now();
        trace();
        mrays.push_back(double(rays) / std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() * 1e-6);
    }
    auto [lo, hi] = std::minmax_element(mrays.begin(), mrays.end());
    return {{"mrays_median", median(mrays)}, {"mrays_min", *lo}, {"mrays_max", *hi}, {"mrays_runs", mrays}};
}

// Steps per ray, and CPU cycles per ray-step where a CPU traced (threads > 0).
void add_costs(json& row, std::span<const hit> hits, unsigned threads) {
    double steps = 0;
    for (auto& h : hits) steps += h.steps;
    steps /= double(std::max<std::size_t>(1, hits.size()));
    double clock = cpu_clock_hz(), rate = row["mrays_median"].get<double>() * 1e6;
    row["steps_per_ray"] = steps;
    row["threads"] = threads;
    row["cycles_per_ray_step"] = threads > 0 && clock > 0 && steps > 0 ? threads * clock / (rate * steps) : NAN;
}

// Disagreements of hits with expected ones: closest hits on everything but steps, any hits on status.
std::uint64_t count_mismatches(std::span<const hit> got, std::span<const hit> want, bool any) {
    std::uint64_t n = 0;
    for (std::size_t i = 0; i < got.size(); ++i) {
        if (any) { n += got[i].is_hit() != want[i].is_hit(); continue; }
        hit a = got[i], b = want[i];
        a.steps = b.steps = 0;
        if (a.t == 0.0f && b.t == 0.0f) a.t = b.t = 0.0f;
        n += std::memcmp(&a, &b, sizeof(hit)) != 0;
    }
    return n;
}

std::uint64_t instance_hits(std::span<const hit> hits) {
    std::uint64_t n = 0;
    for (auto& h : hits) n += hit_instance(h) ? 1 : 0;
    return n;
}

// Every instance behind the camera (a cluster 4 scene sizes back along its view), where no
// primary ray, which starts at the eye and goes forward, can meet it.
pose behind_camera(const camera& c, const box3i& world, const pose& p) {
    pose q = p;
    float size = float(std::max({world.extent().x, world.extent().y, world.extent().z}));
    glm::vec3 forward = glm::normalize(c.target - c.position);
    q.position = c.position - forward * (4.0f * size) + (p.position - glm::vec3(world.min)) * 0.25f;
    return q;
}

}  // namespace

int bench_scene_file(const bench_options& o) {
    const std::string& spec = o.scene.scenes.at(0);
    if (o.scene.scenes.size() > 1) fail("bench: one scene file at a time (", o.scene.scenes.size(), " given)");
    if (!o.out.empty()) require_writable(o.out, "--out");
    loaded_scene s = load_scene_description(spec, o.scene);
    std::size_t count = s.description.instances.size();
    box3i world = s.world.bounds();
    camera cam = auto_camera(world, s.world.up_axis, 0);
    auto primary = primary_rays(cam, o.width, o.height);

    std::optional<output_file> out;
    if (!o.out.empty()) {
        out.emplace(o.out, "--out");
        out->stream() << results_header(own_command_line(), 1).dump() << "\n";
    }
    std::printf("%-8s %-17s %-11s %-11s %-7s %-9s %9s %9s %9s %9s %10s\n", "world", "structure", "backend", "candidates",
                "rays", "placement", "Mrays/s", "steps/ray", "cyc/step", "inst.hits", "mismatches");
    int failed = 0;
    auto emit = [&](json row) {
        if (row.contains("mrays_median"))
            std::printf("%-8s %-17s %-11s %-11s %-7s %-9s %9.2f %9.2f %9.1f %9llu %10llu\n",
                        row["world"].get<std::string>().c_str(), row["structure"].get<std::string>().c_str(),
                        row["backend"].get<std::string>().c_str(), row["candidates"].get<std::string>().c_str(),
                        row["ray_set"].get<std::string>().c_str(), row["placement"].get<std::string>().c_str(),
                        row["mrays_median"].get<double>(), row["steps_per_ray"].get<double>(),
                        row["cycles_per_ray_step"].is_number() ? row["cycles_per_ray_step"].get<double>() : 0.0,
                        (unsigned long long)row["instance_hits"].get<std::uint64_t>(),
                        (unsigned long long)row.value("mismatches", std::uint64_t(0)));
        else
            std::printf("%-8s update on %-11s (%s) %zu instances moving: %.3f ms a frame (median of %d), %.0f bytes sent\n",
                        row["world"].get<std::string>().c_str(), row["backend"].get<std::string>().c_str(),
                        row["candidates"].get<std::string>().c_str(), count,
                        row["update_ms_median"].get<double>(), o.runs, row["update_bytes_median"].get<double>());
        std::fflush(stdout);
        failed += row.value("mismatches", std::uint64_t(0)) > 0;
        if (out) out->stream() << row.dump() << "\n" << std::flush;
    };
    json base = {{"type", "row"}, {"scene", scene_label(spec)}, {"world_scene", scene_label(s.description.world)},
                 {"entities", count}, {"model_fields", model_fields_label(s.description)}, {"width", o.width},
                 {"height", o.height}, {"rays", primary.size()}, {"runs", o.runs}};

    bool embree_done = false;
    for (auto& w : split_names(o.structures)) {
        bool has_scenes = false;
        for (auto& name : scene_world_names()) has_scenes |= name == w;
        if (!has_scenes) continue;
        // The ray sets and their expected answers, from the cpu-scalar scene at frame 0.
        std::fprintf(stderr, "building the scene over %s (cpu-scalar, for the expected hits) ...\n", w.c_str());
        auto scalar = make_entity_run(w, "cpu-scalar", s);
        std::vector<hit> primary_hits(primary.size());
        scalar->closest_hit(primary, primary_hits);
        auto shadow = shadow_rays(primary, primary_hits, sun_direction(s.world.up_axis));
        bool brute = double(primary.size()) * double(std::max<std::size_t>(count, 1)) <= 4e8;
        struct ray_set {
            const char* name;
            const std::vector<ray>* rays;
            bool any;
            std::vector<hit> in_view, off_paths, world_alone;  // expected hits
        };
        std::vector<ray_set> sets{{"primary", &primary, false, {}, {}, {}}, {"shadow", &shadow, true, {}, {}, {}}};
        auto expected = [&](entity_run& run, const ray_set& set) {
            if (brute) return run.reference(*set.rays, set.any ? VX_MODE_ANY : VX_MODE_CLOSEST);
            std::vector<hit> h(set.rays->size());
            if (set.any) scalar->any_hit(*set.rays, h);
            else scalar->closest_hit(*set.rays, h);
            return h;
        };
        std::fprintf(stderr, "expected hits (%s) ...\n", brute ? "brute-force reference" : "cpu-scalar scene");
        for (auto& set : sets) {
            set.in_view = expected(*scalar, set);
            set.world_alone.resize(set.rays->size());
            if (set.any) scalar->world_any_hit(*set.rays, set.world_alone);
            else scalar->world_closest_hit(*set.rays, set.world_alone);
        }
        auto off = [&](std::uint32_t i) { return behind_camera(cam, world, s.description.instances[i].start); };
        scalar->move_all(off);
        for (auto& set : sets) set.off_paths = expected(*scalar, set);

        for (auto& b : split_names(o.backends)) {
            std::fprintf(stderr, "scene over %s on %s ...\n", w.c_str(), b.c_str());
            auto run = make_entity_run(w, b, s);
            for (auto& set : sets) {
                std::vector<hit> hits(set.rays->size());
                std::uint64_t mismatches = 0;
                auto measure = [&](const char* placement, const std::string& candidates, const std::vector<hit>& want,
                                   auto&& trace) {
                    json row = base;
                    row.update({{"world", w}, {"structure", "scene-" + w}, {"backend", b}, {"device", run->device()},
                                {"ray_set", set.name}, {"placement", placement}, {"candidates", candidates},
                                {"validated_by", brute ? "reference" : "cpu-scalar"}});
                    if (std::string(placement) == "none") row["structure"] = w, row["entities"] = 0;
                    mismatches = 0;
                    row.update(time_runs(o, hits.size(), [&] {
                        trace();
                        mismatches += count_mismatches(hits, want, set.any);
                    }));
                    add_costs(row, hits, run->cpu_threads());
                    row["instance_hits"] = instance_hits(hits);
                    row["mismatches"] = mismatches;
                    emit(row);
                };
                measure("none", "-", set.world_alone, [&] {
                    if (set.any) run->world_any_hit(*set.rays, hits);
                    else run->world_closest_hit(*set.rays, hits);
                });
                auto trace_scene = [&] {
                    if (set.any) run->any_hit(*set.rays, hits);
                    else run->closest_hit(*set.rays, hits);
                };
                for (auto& c : split_names(o.candidates)) {
                    run->set_candidates(candidates_named(c));
                    run->move_all(off);
                    measure("off-paths", c, set.off_paths, trace_scene);
                    run->go_to(0);
                    measure("in-view", c, set.in_view, trace_scene);
                }
            }
            for (auto& c : split_names(o.candidates)) {
                run->set_candidates(candidates_named(c));
                run->go_to(0);
                std::vector<double> ms, bytes;
                for (int f = 1; f <= o.runs; ++f) {
                    run->go_to(f);
                    ms.push_back(run->seconds_last_update() * 1e3);
                    bytes.push_back(double(run->bytes_last_update()));
                }
                json row = base;
                row.update({{"type", "update"}, {"world", w}, {"backend", b}, {"candidates", c}, {"moved", count},
                            {"update_ms_median", median(ms)}, {"update_ms_runs", ms}, {"update_bytes_median", median(bytes)}});
                emit(row);
            }
        }

#if VOXRAY_WITH_EMBREE
        if (!embree_done) {  // once, on the first world kind's rays (the same rays for every kind)
            embree_done = true;
            std::fprintf(stderr, "Embree's instancing peer ...\n");
            embree::instanced_scene peer(s.world);
            for (auto& m : s.models) peer.add_model(m);
            for (std::size_t i = 0; i < count; ++i) peer.add(s.model_of[i], s.description.instances[i].start);
            peer.commit();
            embree::trace_options opt;
            opt.threads = 0;
            for (auto& set : sets) {
                std::vector<hit> hits(set.rays->size());
                for (const char* placement : {"in-view", "off-paths"}) {
                    bool in_view = std::string(placement) == "in-view";
                    for (std::size_t i = 0; i < count; ++i)
                        peer.move(std::uint32_t(i), in_view ? s.description.instances[i].start : off(std::uint32_t(i)));
                    peer.commit();
                    const auto& want = in_view ? set.in_view : set.off_paths;
                    std::uint64_t disagreements = 0;
                    json row = base;
                    row.update({{"world", "-"}, {"structure", "embree-instances"}, {"backend", "cpu"}, {"device", "embree"},
                                {"ray_set", set.name}, {"placement", placement}, {"candidates", "embree"}});
                    row.update(time_runs(o, hits.size(), [&] {
                        if (set.any) peer.any_hit(*set.rays, hits, opt);
                        else peer.closest_hit(*set.rays, hits, opt);
                        disagreements += count_mismatches(hits, want, true);
                    }));
                    add_costs(row, hits, std::thread::hardware_concurrency());
                    row["steps_per_ray"] = NAN;
                    row["cycles_per_ray_step"] = NAN;
                    row["instance_hits"] = instance_hits(hits);
                    row["status_disagreements"] = disagreements;
                    row["commit_ms"] = peer.commit_seconds() * 1e3;
                    emit(row);
                }
            }
        }
#endif
    }
    if (out) out->finish();
    std::printf("%s; %d rows with mismatches\n", o.out.empty() ? "done" : ("results in " + o.out).c_str(), failed);
    return failed == 0 ? 0 : 1;
}

}  // namespace voxray::tool
