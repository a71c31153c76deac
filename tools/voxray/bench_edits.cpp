// voxray bench --edits: the brickmap paper's editing load. 50 balls of radius 25 bounce
// through the world; each frame erases every ball and fills it at its new place (100
// sphere edits in one batch), then brings the backend up to date with only the changed
// words. --edits voxel: the smallest edit, one voxel a frame.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>

#include <nlohmann/json.hpp>

#include "bench_options.hpp"
#include "cli.hpp"
#include "edits.hpp"
#include "engines.hpp"
#include "output.hpp"
#include "units.hpp"

namespace voxray::tool {

int run_edit_bench(const bench_options& o) {
    auto names = split_names(o.structures), backends = split_names(o.backends);
    if (names.size() != 1 || backends.size() != 1 || o.scene.scenes.size() != 1)
        fail("--edits measures one SCENE, one --structure and one --backend, not ", o.scene.scenes.size(), " x ",
             names.size(), " x ", backends.size());
    if (!o.out.empty()) require_writable(o.out, "--out");
    const std::string &structure_name = names[0], &backend = backends[0], &kind = o.edits;
    const int frames = o.runs;
    constexpr int balls = 50, radius = 25;

    auto model = load_scene(o.scene.scenes[0], o.scene);
    box3i world = model.bounds();
    if (world.empty()) fail("scene ", o.scene.scenes[0], " has no voxels: its world is empty, so there is nowhere to edit");
    auto structure = build_structure(structure_name, model);
    if (!structure->editable()) fail("--edits needs an editable structure, not ", structure_name);
    auto engine = structure->trace_on(backend);
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

    double edit_seconds = 0, update_seconds = 0, refine_seconds = 0;
    std::uint64_t writes = 0, uploaded = 0;
    std::vector<region_edit> edits;
    // Frame 0 is a warm-up, not counted: a map built to size grows its brick pool on its
    // first new brick, and that update sends the whole (reallocated) blob once.
    for (int f = 0; f <= frames; ++f) {
        std::fprintf(stderr, "frame %d/%d ...\r", f, frames);
        edits.clear();
        if (kind == "voxel") {
            glm::ivec3 e = world.extent(), p = world.min + glm::ivec3(g.below(e.x), g.below(e.y), g.below(e.z));
            edits.push_back({regions::box{box3i{p, p + 1}}, edit_op::fill, std::uint32_t(1 + g.below(255))});
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
            structure->apply_edits(edits, o.threads);
            engine->after_edits(model);
            continue;
        }
        auto start = std::chrono::steady_clock::now();
        structure->apply_edits(edits, o.threads);  // edits, then takes the dirty ranges
        auto edited = std::chrono::steady_clock::now();
        engine->after_edits(model);
        auto synced = std::chrono::steady_clock::now();
        edit_seconds += std::chrono::duration<double>(edited - start).count();
        refine_seconds += structure->last_refine_seconds();
        update_seconds += std::chrono::duration<double>(synced - edited).count();
        uploaded += engine->bytes_uploaded_last_update();
    }
    std::fprintf(stderr, "\n");
    double per_second = double(writes) / edit_seconds;
    double per_update = double(uploaded) / frames;
    std::printf("scene %s  structure %s  backend %s (%s)  %d frames of %s, %u threads\n", o.scene.scenes[0].c_str(),
                structure_name.c_str(), backend.c_str(), engine->device().c_str(), frames,
                kind == "voxel" ? "one voxel edit" : "100 sphere edits (50 balls, r 25)", o.threads);
    std::printf("world %d x %d x %d, blob %s; per frame %s of edits (%s of it regrowing fields) and %s of update\n",
                world.extent().x, world.extent().y, world.extent().z, human_bytes(double(structure->bytes())).c_str(),
                human_seconds(edit_seconds / frames).c_str(), human_seconds(refine_seconds / frames).c_str(),
                human_seconds(update_seconds / frames).c_str());
    if (!o.out.empty()) {
        nlohmann::json j = {{"scene", o.scene.scenes[0]}, {"structure", structure_name}, {"backend", backend},
                            {"edits", kind}, {"threads", o.threads}, {"frames", frames}, {"voxel_writes", writes},
                            {"writes_per_second", per_second}, {"bytes_uploaded_per_update", per_update},
                            {"refine_ms", 1e3 * refine_seconds / frames},
                            {"writes_per_second_without_refine", double(writes) / (edit_seconds - refine_seconds)},
                            {"blob_bytes", structure->bytes()}, {"update_ms", 1e3 * update_seconds / frames}};
        output_file out(o.out, "--out");
        out.stream() << j.dump() << "\n";
        out.finish();
    }
    std::printf("edits: %s (%s without regrowing fields), %s uploaded per update\n",
                human_rate(per_second, "voxel writes").c_str(),
                human_rate(double(writes) / (edit_seconds - refine_seconds), "voxel writes").c_str(),
                human_bytes(per_update).c_str());
    return 0;
}

}  // namespace voxray::tool
