// The world build over the ranks of an MPI communicator (component voxray::mpi: needs
// <mpi.h>; the rest of voxray builds without it). Every rank reads the source itself (a
// scene or mesh on a shared filesystem) and writes its chunks into the shared folder;
// nothing large goes over MPI: the plan, a counter, the chunk lists (32 bytes a chunk).
//
//   MPI_Init(...);
//   build_world_mpi(model_source(model), "world/", options, MPI_COMM_WORLD);  // on every rank
//
// 1. Every rank makes the plan (world/build/shard_plan.hpp, N = ranks) and compares it
//    with rank 0's: a rank started with other arguments is refused, naming the difference.
// 2. Rank 0 locks and claims the folder (world/build/world_build.hpp).
// 3. The units, up to the split LOD: `dynamic` hands them out heaviest first from a counter
//    on rank 0 (one MPI_Fetch_and_op a unit: a rank that finishes early takes the next);
//    `static_split` gives each rank its balanced share, as --shard K/N does.
// 4. The LODs above the split, level by level with a barrier each: the ranks share each
//    level's chunks (the same two schedules) and then every rank learns them.
// 5. Rank 0 writes the manifest.
// A failure on any rank fails the build on every rank with that rank's message (no rank
// waits forever on one that threw). A killed rank takes mpirun's job down; running it
// again resumes, as every build does. The folder is byte for byte the one build_world writes.
#pragma once
// The C API only: Open MPI's and MPICH's deprecated C++ bindings are not needed.
#ifndef OMPI_SKIP_MPICXX
#define OMPI_SKIP_MPICXX 1
#endif
#ifndef MPICH_SKIP_MPICXX
#define MPICH_SKIP_MPICXX 1
#endif
#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include "voxray/world/build/sharded_build.hpp"

namespace voxray {

enum class mpi_schedule { dynamic, static_split };

namespace mpi_build_detail {

}  // namespace mpi_build_detail

// What every rank throws when one failed (mpi_build_detail::agree): the same message on
// each, so one rank's report says it all.
struct mpi_ranks_failed : error {
    explicit mpi_ranks_failed(const std::string& what) : error(what) {}
};

namespace mpi_build_detail {

// Collective: when any rank failed, every rank throws mpi_ranks_failed with the lowest
// failing rank's message, "rank R of N: ...".
inline void agree(MPI_Comm comm, const std::string& failure) {
    int rank = 0, size = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &size);
    int mine = failure.empty() ? size : rank, first = size;
    MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
    if (first == size) return;
    char text[2048] = {};
    if (rank == first) std::strncpy(text, failure.c_str(), sizeof text - 1);
    MPI_Bcast(text, int(sizeof text), MPI_CHAR, first, comm);
    throw mpi_ranks_failed("rank " + std::to_string(first) + " of " + std::to_string(size) + ": " + text);
}

// Runs f, and agree()s on its failure.
template <class F>
void together(MPI_Comm comm, F&& f) {
    std::string failure;
    try {
        f();
    } catch (const std::exception& e) {
        failure = e.what();
        if (failure.empty()) failure = "world build: an error without a message";
    }
    agree(comm, failure);
}

// A chunk list entry as 4 words: lod and x, y and z, voxels, file bytes.
inline std::vector<std::uint64_t> pack(const std::vector<manifest_chunk>& chunks) {
    std::vector<std::uint64_t> out;
    for (auto& c : chunks) {
        out.push_back(std::uint64_t(std::uint32_t(c.key.lod)) << 32 | std::uint32_t(c.key.cell.x));
        out.push_back(std::uint64_t(std::uint32_t(c.key.cell.y)) << 32 | std::uint32_t(c.key.cell.z));
        out.push_back(c.voxel_count);
        out.push_back(c.file_bytes);
    }
    return out;
}
inline std::vector<manifest_chunk> unpack(const std::vector<std::uint64_t>& words) {
    std::vector<manifest_chunk> out;
    for (std::size_t i = 0; i + 4 <= words.size(); i += 4) {
        manifest_chunk c;
        c.key.lod = int(std::uint32_t(words[i] >> 32));
        c.key.cell = {int(std::uint32_t(words[i])), int(std::uint32_t(words[i + 1] >> 32)), int(std::uint32_t(words[i + 1]))};
        c.voxel_count = words[i + 2];
        c.file_bytes = words[i + 3];
        out.push_back(c);
    }
    return out;
}

// The plan as numbers, in shard_files.hpp's field order.
inline std::vector<std::int64_t> plan_numbers(const shard_plan& p) {
    std::vector<std::int64_t> out;
    for (auto& f : shard_files_detail::fields) out.push_back(f.get(p));
    return out;
}

// Every rank's chunks, on every rank.
inline std::vector<manifest_chunk> allgather_chunks(MPI_Comm comm, const std::vector<manifest_chunk>& mine) {
    int size = 1;
    MPI_Comm_size(comm, &size);
    auto words = pack(mine);
    long long count = (long long)words.size();
    auto ranks = std::size_t(size);
    std::vector<long long> counts(ranks, 0);
    MPI_Allgather(&count, 1, MPI_LONG_LONG, counts.data(), 1, MPI_LONG_LONG, comm);
    long long total = std::accumulate(counts.begin(), counts.end(), 0ll);
    if (total > 0x7fffffffll) fail("world build: ", total / 4, " chunks are too many to gather over MPI");
    std::vector<int> ints(ranks, 0), offsets(ranks, 0);
    for (std::size_t r = 0; r < ranks; ++r) {
        ints[r] = int(counts[r]);
        if (r) offsets[r] = offsets[r - 1] + ints[r - 1];
    }
    std::vector<std::uint64_t> all(static_cast<std::size_t>(total), 0);
    MPI_Allgatherv(words.data(), int(count), MPI_UINT64_T, all.data(), ints.data(), offsets.data(), MPI_UINT64_T, comm);
    return unpack(all);
}

// Calls job(i) for the items i in [0, n) this rank takes: each rank takes the next one
// as it becomes free, from a counter on rank 0 (one MPI_Fetch_and_op an item). Collective;
// a failure fails every rank (agree) once every item is taken.
template <class Job>
void take_in_turn(MPI_Comm comm, std::size_t n, Job&& job) {
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    long long* counter = nullptr;
    MPI_Win win;
    MPI_Win_allocate(rank == 0 ? MPI_Aint(sizeof(long long)) : 0, sizeof(long long), MPI_INFO_NULL, comm, &counter, &win);
    if (rank == 0) {
        MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, win);
        *counter = 0;
        MPI_Win_unlock(0, win);
    }
    MPI_Barrier(comm);
    std::string failure;
    for (;;) {
        long long one = 1, next = 0;
        MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, win);
        MPI_Fetch_and_op(&one, &next, MPI_LONG_LONG, 0, 0, MPI_SUM, win);
        MPI_Win_unlock(0, win);
        if (next >= (long long)n) break;
        if (!failure.empty()) continue;  // keep taking items, so the others finish sooner
        try {
            job(std::size_t(next));
        } catch (const std::exception& e) {
            failure = e.what();
        }
    }
    MPI_Win_free(&win);
    agree(comm, failure);
}

// Sums the per-LOD counts of every rank's report into rank 0's (the others keep theirs).
inline void reduce_report(MPI_Comm comm, world_build_report& r) {
    std::vector<std::uint64_t> mine;
    for (auto& l : r.lods) mine.insert(mine.end(), {l.chunks, l.voxels, l.disk_bytes, l.resumed});
    mine.push_back(r.cells_scanned);
    std::vector<std::uint64_t> sum(mine.size());
    MPI_Reduce(mine.data(), sum.data(), int(mine.size()), MPI_UINT64_T, MPI_SUM, 0, comm);
    int rank = 0;
    MPI_Comm_rank(comm, &rank);
    if (rank != 0) return;
    for (std::size_t n = 0; n < r.lods.size(); ++n) {
        r.lods[n].chunks = sum[4 * n], r.lods[n].voxels = sum[4 * n + 1];
        r.lods[n].disk_bytes = sum[4 * n + 2], r.lods[n].resumed = sum[4 * n + 3];
    }
    r.cells_scanned = sum.back();
}

}  // namespace mpi_build_detail

// Called on every rank of `comm`; returns the whole build's report on rank 0 (counts
// summed over ranks) and each rank's own elsewhere.
template <class Source>
world_build_report build_world_mpi(const Source& source, const std::filesystem::path& dir, const world_build_options& o,
                                   MPI_Comm comm, mpi_schedule schedule = mpi_schedule::dynamic) {
    using namespace mpi_build_detail;
    int rank = 0, size = 1;
    MPI_Comm_rank(comm, &rank);
    MPI_Comm_size(comm, &size);
    std::unique_ptr<world_builder<Source>> b;
    shard_split split;
    together(comm, [&] {
        b = std::make_unique<world_builder<Source>>(source, dir, o);
        const world_grid& g = b->header().grid;
        auto cells = source.cells(g);
        split = shard_split::make(cells, cell_work(source, g, cells), g.top_lod, unsigned(size));
    });
    // 1. The same plan everywhere.
    shard_plan mine = sharded_build_detail::plan_of(source, o, unsigned(size), split.split_lod);
    auto numbers = plan_numbers(mine), first = numbers;
    MPI_Bcast(first.data(), int(first.size()), MPI_INT64_T, 0, comm);
    together(comm, [&] {
        shard_plan zero;
        for (std::size_t i = 0; i < first.size(); ++i) shard_files_detail::fields[i].set(zero, first[i]);
        if (auto d = plan_difference(zero, mine, "on rank 0"); !d.empty())
            fail("world build: ranks started with other arguments: ", d);
    });
    // 2. The folder, by rank 0 alone.
    std::unique_ptr<world_build_detail::folder_lock> lock;
    together(comm, [&] {
        if (rank != 0) return;
        lock = std::make_unique<world_build_detail::folder_lock>(dir);
        b->claim_folder();
    });
    // 3. The units, from the source up to the split.
    std::vector<manifest_chunk> chunks;
    if (schedule == mpi_schedule::static_split) {
        together(comm, [&] {
            std::vector<glm::ivec3> cells;
            for (std::size_t u : split.share(unsigned(rank), unsigned(size)))
                cells.insert(cells.end(), split.units[u].cells.begin(), split.units[u].cells.end());
            b->build_up_from_source(cells, split.split_lod, chunks);
        });
    } else {
        std::vector<std::size_t> order(split.units.size());
        std::iota(order.begin(), order.end(), std::size_t(0));
        std::stable_sort(order.begin(), order.end(), [&](auto a, auto c) { return split.units[a].work > split.units[c].work; });
        take_in_turn(comm, order.size(), [&](std::size_t next) {
            b->build_up_from_source(split.units[order[next]].cells, split.split_lod, chunks);
        });
    }
    // 4. The LODs above the split, level by level (a barrier each): every rank builds its
    // part of the level from the files below, then all learn the level's chunks.
    auto all = allgather_chunks(comm, chunks);
    const world_grid& g = b->header().grid;
    for (int lod = split.split_lod + 1; lod <= g.top_lod; ++lod) {
        auto in = world_builder<Source>::level_above(all, lod);
        std::vector<manifest_chunk> level;
        if (schedule == mpi_schedule::static_split) {
            std::vector<glm::ivec3> mine;
            for (std::size_t i = std::size_t(rank); i < in.cells.size(); i += std::size_t(size)) mine.push_back(in.cells[i]);
            together(comm, [&] { b->build_level_from_below(lod, mine, in.below, level); });
        } else {
            take_in_turn(comm, in.cells.size(),
                         [&](std::size_t next) { b->build_level_from_below(lod, {in.cells[next]}, in.below, level); });
        }
        auto built = allgather_chunks(comm, level);
        all.insert(all.end(), built.begin(), built.end());
    }
    // 5. The manifest, on rank 0.
    reduce_report(comm, b->report());
    together(comm, [&] {
        if (rank == 0) b->write_manifest_of(std::move(all));
    });
    b->report().seconds = b->seconds();
    return b->report();
}

}  // namespace voxray
