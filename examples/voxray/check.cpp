// voxray check: every structure x backend against the reference (dense grid, cpu-scalar)
// on the same rays; per pair the mismatch and tie counts (see check/compare.hpp).
#include <cstdio>

#include "args.hpp"
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

int run_check(int argc, char** argv) {
    args a(argc, argv, 2, {"rays", "structures", "backends", "seed", "resolution"});
    if (a.positional().size() != 1) fail("check takes one SCENE");
    auto count = std::size_t(a.number("rays", 1000000, 1, 100000000));
    auto seed = std::uint64_t(a.number("seed", 1, 0, 1ll << 62));
    auto structures = a.list("structures", "dense,embree-boxes");
    auto backends = a.list("backends", "cpu,cpu-scalar,opencl,vulkan");
    auto model = load_scene(a.positional()[0], int(a.number("resolution", 512, 1, 4096)));

    auto rays = check_rays(model.bounds(), model.up_axis, count, seed);
    std::fprintf(stderr, "tracing %zu rays on the reference (dense, cpu-scalar) ...\n", rays.size());
    auto reference_grid = build_structure("dense", model);
    std::vector<hit> reference(rays.size()), hits(rays.size());
    make_traceable(reference_grid, "cpu-scalar")->closest_hit(rays, reference);

    std::uint64_t pairs = 0, mismatches = 0, ties = 0;
    std::printf("%-14s %-11s %12s %10s\n", "structure", "backend", "mismatches", "ties");
    for (auto& s : structures) {
        auto structure = s == "dense" ? reference_grid : build_structure(s, model);
        for (auto& b : backends) {
            if (!pair_exists(s, b)) {
                std::printf("%-14s %-11s %s\n", s.c_str(), b.c_str(), "(pair does not exist: not counted)");
                continue;
            }
            std::fprintf(stderr, "checking %s on %s ...\n", s.c_str(), b.c_str());
            make_traceable(structure, b)->closest_hit(rays, hits);
            agreement_counts counts;
            int shown = 0;
            for (std::size_t i = 0; i < rays.size(); ++i) {
                auto verdict = compare_hits(rays[i], reference[i], hits[i]);
                counts.add(verdict);
                if (verdict == agreement::mismatch && shown++ < 3) print_mismatch(i, rays[i], reference[i], hits[i]);
            }
            std::printf("%-14s %-11s %12llu %10llu\n", s.c_str(), b.c_str(), (unsigned long long)counts.mismatches,
                        (unsigned long long)counts.ties);
            ++pairs;
            mismatches += counts.mismatches;
            ties += counts.ties;
        }
    }
    std::printf("checked %zu rays x %llu pairs: %llu mismatches, %llu ties\n", rays.size(), (unsigned long long)pairs,
                (unsigned long long)mismatches, (unsigned long long)ties);
    return mismatches == 0 ? 0 : 1;
}

}  // namespace voxray::tool
