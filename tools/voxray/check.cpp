// voxray check: every structure x backend against the reference (dense grid, cpu-scalar)
// on the same rays; per pair the mismatch and tie counts (see check/compare.hpp). A check
// that compared nothing fails.
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "cli.hpp"
#include "edits.hpp"
#include "mesh_check.hpp"
#include "engines.hpp"
#include "entity_scene.hpp"
#include "output.hpp"
#include "scene.hpp"
#include "voxray/check/compare.hpp"
#include "voxray/check/ray_sets.hpp"

namespace voxray::tool {

namespace {

struct check_options {
    scene_options scene;
    std::size_t rays = 1000000;
    std::uint64_t seed = 1;
    int edits = 0, frames = 1;
    bool rays_given = false;
    std::string structures = exact_structure_names(), backends, json, candidates = all_candidates();
    bool mesh = false;
    mesh_check_options mesh_options;
};

void print_hit(const char* label, const hit& h) {
    std::printf("    %-9s %s t=%.9g voxel=(%d, %d, %d) face=%s material=%u\n", label, h.is_hit() ? "hit " : "miss", h.t,
                h.voxel.x, h.voxel.y, h.voxel.z, face_name(h.normal), h.material);
}

// The first few mismatches of a pair, with everything needed to replay the ray.
void print_mismatch(std::size_t index, const ray& r, const hit& expected, const hit& got) {
    std::printf("  mismatch at ray %zu: origin (%.9g, %.9g, %.9g) direction (%.9g, %.9g, %.9g) t [%.9g, %.9g]\n", index,
                r.origin.x, r.origin.y, r.origin.z, r.direction.x, r.direction.y, r.direction.z, r.tmin, r.tmax);
    print_hit("reference", expected);
    print_hit("got", got);
}

// Applies the edits to every editable structure through its editing API and to the model
// (the reference), then brings every tracer up to date: each editable structure sends its
// own dirty ranges; the others are rebuilt from the edited model by after_edits().
void apply_edits(const std::vector<region_edit>& edits, voxel_model& model, std::vector<std::shared_ptr<slot>>& structures,
                 std::vector<std::unique_ptr<traceable>>& tracers) {
    box3i world = model.bounds();
    for (auto& s : structures)
        if (s->editable()) s->apply_edits(edits);
    std::uint64_t writes = 0;
    for (auto& e : edits) writes += apply_to_model(model, e, world);
    std::fprintf(stderr, "applied %zu edits (%llu voxel writes); updating every backend ...\n", edits.size(),
                 (unsigned long long)writes);
    for (auto& t : tracers) t->after_edits(model);
}

// A scene file: every world kind with scenes among --structures x every backend, each frame
// against the brute-force reference (entities/reference.hpp), which walks every instance
// for every ray: 20,000 rays a frame unless --rays says otherwise.
int check_scene(const check_options& o) {
    if (o.edits > 0 || o.mesh || !o.json.empty()) fail("--edits, --mesh and --json do not apply to a scene file");
    std::string worlds;
    for (auto& w : scene_world_names())
        for (auto& s : split_names(o.structures))
            if (s == w) worlds += (worlds.empty() ? "" : ",") + w;
    if (worlds.empty()) {
        std::string with;
        for (auto& w : scene_world_names()) with += (with.empty() ? "" : ", ") + w;
        fail("--structures ", o.structures, ": none has scenes with entities (those that do: ", with, ")");
    }
    return check_scene_file(o.scene.scenes[0], o.scene, o.frames, o.rays_given ? o.rays : 20000, o.seed, worlds, o.backends,
                            o.candidates);
}

int check(const check_options& o) {
    if (!o.json.empty()) require_writable(o.json, "--json");
    if (is_scene_description(o.scene.scenes[0])) return check_scene(o);
    if (o.frames != 1) fail("--frames ", o.frames, ": only a scene file (.json) has frames");
    auto model = load_scene(o.scene.scenes[0], o.scene);
    box3i world = model.bounds();
    if (o.mesh) {
        std::uint64_t mismatches = check_mesh(model, o.mesh_options);
        std::printf("mesh check of %s: %llu mismatches\n", scene_label(o.scene.scenes[0]).c_str(), (unsigned long long)mismatches);
        return mismatches == 0 ? 0 : 1;
    }

    // Every pair is set up before any edit, so that edits reach it through update().
    std::vector<std::shared_ptr<slot>> structures;
    std::vector<std::unique_ptr<traceable>> tracers;
    std::vector<std::pair<std::string, std::string>> labels;
    std::vector<std::shared_ptr<slot>> slot_of;  // per pair
    std::string absent;  // pairs that do not exist, named after the results
    for (auto& s : split_names(o.structures)) {
        std::fprintf(stderr, "building %s ...\n", s.c_str());
        structures.push_back(build_structure(s, model));
        for (auto& b : split_names(o.backends)) {
            if (!structures.back()->runs_on(b)) {
                absent += (absent.empty() ? "" : ", ") + s + " on " + b;
                continue;
            }
            tracers.push_back(structures.back()->trace_on(b));
            slot_of.push_back(structures.back());
            labels.emplace_back(s, b);
        }
    }
    if (tracers.empty()) fail("no structure x backend pair exists among --structures ", o.structures, " and --backends ", o.backends, ": nothing to check");
    if (o.edits > 0 && world.empty()) fail("--edits ", o.edits, ": the scene has no voxels, so no world to edit");
    if (o.edits > 0) apply_edits(random_edits(world, o.edits, o.seed ^ 0x5eed), model, structures, tracers);

    auto rays = check_rays(world, model.up_axis, o.rays, o.seed);
    std::fprintf(stderr, "tracing %zu rays on the reference (dense, cpu-scalar) ...\n", rays.size());
    std::vector<hit> reference(rays.size()), hits(rays.size());
    build_structure("dense", model)->trace_on("cpu-scalar")->closest_hit(rays, reference);

    std::printf("%-14s %-11s %12s %10s\n", "structure", "backend", "mismatches", "ties");
    nlohmann::json pairs = nlohmann::json::array();
    std::uint64_t mismatches = 0, ties = 0;
    for (std::size_t p = 0; p < tracers.size(); ++p) {
        auto& [s, b] = labels[p];
        std::fprintf(stderr, "checking %s on %s ...\n", s.c_str(), b.c_str());
        tracers[p]->closest_hit(rays, hits);
        agreement_counts counts;
        int shown = 0;
        auto tolerance = slot_of[p]->colour_tolerance();  // hits with colours: within it of the palette's
        for (std::size_t i = 0; i < rays.size(); ++i) {
            auto verdict = tolerance ? compare_colour_hits(rays[i], reference[i], hits[i], model.palette(), *tolerance)
                                     : compare_hits(rays[i], reference[i], hits[i]);
            counts.add(verdict);
            if (verdict == agreement::mismatch && shown++ < 3) print_mismatch(i, rays[i], reference[i], hits[i]);
        }
        std::printf("%-14s %-11s %12llu %10llu\n", s.c_str(), b.c_str(), (unsigned long long)counts.mismatches,
                    (unsigned long long)counts.ties);
        pairs.push_back({{"structure", s}, {"backend", b}, {"device", tracers[p]->device()}, {"rays", counts.rays},
                         {"same", counts.same}, {"ties", counts.ties}, {"mismatches", counts.mismatches}});
        mismatches += counts.mismatches;
        ties += counts.ties;
    }
    std::printf("checked %zu rays x %zu pairs: %llu mismatches, %llu ties\n", rays.size(), tracers.size(),
                (unsigned long long)mismatches, (unsigned long long)ties);
    if (!absent.empty()) std::printf("not counted (these pairs do not exist): %s\n", absent.c_str());
    if (!o.json.empty()) {
        nlohmann::json doc = {{"scene", o.scene.scenes[0]}, {"voxels", model.voxel_count()}, {"rays", rays.size()},
                              {"seed", o.seed},           {"edits", o.edits},                {"pairs", pairs},
                              {"mismatches", mismatches}, {"ties", ties},                    {"passed", mismatches == 0}};
        output_file out(o.json, "--json");
        out.stream() << doc.dump(2) << "\n";
        out.finish();
    }
    return mismatches == 0 ? 0 : 1;
}

}  // namespace

command add_check(CLI::App& parent) {
    auto* app = parent.add_subcommand("check", "every structure x backend against the reference on the same rays");
    auto o = std::make_shared<check_options>();
    o->backends = join_names(backend_names());
    o->scene.add_to(app, false);
    auto* rays = app->add_option("--rays", o->rays, "rays to trace (half camera rays, half random)")
        ->check(CLI::Range(std::size_t(1), std::size_t(100000000)))->capture_default_str();
    app->add_option("--frames", o->frames, "frames of a scene file's motion, each checked")
        ->check(CLI::Range(1, 100000))->capture_default_str();
    app->add_option("--structures", o->structures, "structures to check")
        ->check(names_from(all_structure_names(), "structure"))->capture_default_str();
    app->add_option("--backends", o->backends, "backends to check")
        ->check(names_from(backend_names(), "backend"))->capture_default_str();
    app->add_option("--seed", o->seed, "seed of the random rays and edits")->capture_default_str();
    app->add_option("--edits", o->edits, "random region edits applied before tracing")
        ->check(CLI::Range(0, 100000))->capture_default_str();
    app->add_option("--json", o->json, "also write the per-pair counts to this JSON file");
    app->add_option("--candidates", o->candidates, "a scene file's ways to find candidate entities, each checked")
        ->check(names_from(candidates_names(), "way"))->capture_default_str();
    app->add_flag("--mesh", o->mesh, "check the scene's chunk meshes instead: face sets, POP order, cracks");
    app->add_option("--mesh-views", o->mesh_options.views, "random views of the mesh crack tests")
        ->check(CLI::Range(1, 10000000))->capture_default_str();
    app->add_option("--mesh-kernel-chunks", o->mesh_options.kernel_chunks,
                    "most chunks (evenly spread) the mesher kernel is compared on, per backend")
        ->check(CLI::Range(std::size_t(1), std::size_t(1) << 24))->capture_default_str();
    return {app, [o, rays] {
        o->mesh_options.seed = o->seed;
        o->rays_given = rays->count() > 0;
        return check(*o);
    }};
}

}  // namespace voxray::tool
