// Parallel generation of a model chunk by chunk: a procedural scene is a
// function of position, so every 16^3 chunk can be filled on its own thread and
// moved into the model whole (voxel_model::replace_chunk), with no per-voxel
// hash lookups. Results do not depend on the thread count.
#pragma once
#include <algorithm>
#include <atomic>
#include <memory>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "voxray/model/build_threads.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::scenes {

// Calls fill(chunk_coord, chunk&) for each chunk of each job on `threads`
// threads (0: all hardware threads); a job is a chunk column (x, y) with a z
// range of chunks, since scenes know their height per column. `fill` gets an
// all-empty chunk and sets what it wants; chunks left empty are dropped.
struct chunk_column_job {
    int cx = 0, cy = 0, cz0 = 0, cz1 = -1;  // chunk coordinates, z inclusive
};

template <class Fill>
void build_chunks(voxel_model& model, const std::vector<chunk_column_job>& jobs, unsigned threads, Fill&& fill) {
    threads = resolve_build_threads(threads, jobs.size());
    struct placed {
        glm::ivec3 coord;
        std::unique_ptr<voxel_model::chunk> data;
    };
    std::vector<std::vector<placed>> results(threads);
    std::atomic<std::size_t> next{0};
    run_build_threads(threads, [&](unsigned id) {
        std::unique_ptr<voxel_model::chunk> spare;
        for (std::size_t k; (k = next.fetch_add(1)) < jobs.size();) {
            auto& job = jobs[k];
            for (int cz = job.cz0; cz <= job.cz1; ++cz) {
                if (!spare) spare = std::make_unique<voxel_model::chunk>();
                glm::ivec3 cc{job.cx, job.cy, cz};
                fill(cc, *spare);
                bool any = std::any_of(spare->voxels.begin(), spare->voxels.end(), [](auto v) { return v != 0; });
                if (any) results[id].push_back({cc, std::move(spare)});
            }
        }
    });
    std::size_t total = model.chunk_count();
    for (auto& r : results) total += r.size();
    model.reserve_chunks(total);
    for (auto& r : results)
        for (auto& p : r) model.replace_chunk(p.coord, std::move(p.data));
}

}  // namespace voxray::scenes
