// voxray check: every structure x backend against the reference (dense grid, cpu-scalar)
// on the same rays; per pair the mismatch and tie counts (see check/compare.hpp).
#include <cstdio>

#include "args.hpp"
#include "edits.hpp"
#include "commands.hpp"
#include "engines.hpp"
#include "scene.hpp"
#include "voxray/check/compare.hpp"
#include "voxray/check/ray_sets.hpp"

namespace voxray::tool {

namespace {

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

}  // namespace

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

int run_check(int argc, char** argv) {
    args a(argc, argv, 2, {"rays", "structures", "backends", "seed", "resolution", "edits"});
    if (a.positional().size() != 1) fail("check takes one SCENE");
    auto count = std::size_t(a.number("rays", 1000000, 1, 100000000));
    auto seed = std::uint64_t(a.number("seed", 1, 0, 1ll << 62));
    int edit_count = int(a.number("edits", 0, 0, 100000));
    auto structure_names = a.list("structures", "dense,brickmap,embree-boxes");
    auto backend_names = a.list("backends", "cpu,cpu-scalar,opencl,vulkan");
    auto model = load_scene(a.positional()[0], int(a.number("resolution", 512, 1, 4096)));
    box3i world = model.bounds();

    // Every pair is set up before any edit, so that edits reach it through update().
    std::vector<std::shared_ptr<slot>> structures;
    std::vector<std::unique_ptr<traceable>> tracers;
    std::vector<std::pair<std::string, std::string>> labels;
    std::printf("%-14s %-11s %12s %10s\n", "structure", "backend", "mismatches", "ties");
    for (auto& s : structure_names) {
        std::fprintf(stderr, "building %s ...\n", s.c_str());
        structures.push_back(build_structure(s, model));
        for (auto& b : backend_names) {
            if (!structures.back()->runs_on(b)) {
                std::printf("%-14s %-11s %s\n", s.c_str(), b.c_str(), "(pair does not exist: not counted)");
                continue;
            }
            tracers.push_back(structures.back()->trace_on(b));
            labels.emplace_back(s, b);
        }
    }
    if (edit_count > 0) apply_edits(random_edits(world, edit_count, seed ^ 0x5eed), model, structures, tracers);

    auto rays = check_rays(world, model.up_axis, count, seed);
    std::fprintf(stderr, "tracing %zu rays on the reference (dense, cpu-scalar) ...\n", rays.size());
    std::vector<hit> reference(rays.size()), hits(rays.size());
    build_structure("dense", model)->trace_on("cpu-scalar")->closest_hit(rays, reference);

    std::uint64_t mismatches = 0, ties = 0;
    for (std::size_t p = 0; p < tracers.size(); ++p) {
        auto& [s, b] = labels[p];
        std::fprintf(stderr, "checking %s on %s ...\n", s.c_str(), b.c_str());
        tracers[p]->closest_hit(rays, hits);
        agreement_counts counts;
        int shown = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            auto verdict = compare_hits(rays[i], reference[i], hits[i]);
            counts.add(verdict);
            if (verdict == agreement::mismatch && shown++ < 3) print_mismatch(i, rays[i], reference[i], hits[i]);
        }
        std::printf("%-14s %-11s %12llu %10llu\n", s.c_str(), b.c_str(), (unsigned long long)counts.mismatches,
                    (unsigned long long)counts.ties);
        mismatches += counts.mismatches;
        ties += counts.ties;
    }
    std::printf("checked %zu rays x %zu pairs: %llu mismatches, %llu ties\n", rays.size(), tracers.size(),
                (unsigned long long)mismatches, (unsigned long long)ties);
    return mismatches == 0 ? 0 : 1;
}

}  // namespace voxray::tool
