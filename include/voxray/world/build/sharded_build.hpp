// A world built by N independent processes (batch jobs: a Slurm array, Kubernetes jobs),
// then finished once:
//
//   for K in 0..N-1, anywhere, in any order, at once or not:  build_world(source, dir, o, {K, N});
//   once every shard is done:                                   finish_world_build(source, dir, o);
//
// Each shard builds its units (world/build/shard_plan.hpp) from the source up to the split
// LOD and lists their chunks in DIR/shards/K-of-N.vxwm; the finish checks that every
// shard is there and of this build, builds the LODs above the split from the files, writes
// the manifest and removes DIR/shards. Every chunk is a function of the source and the
// options alone, so the folder is byte for byte the one build_world writes. A shard or
// finish killed at any moment resumes when run again (chunk files of this build are
// kept); shards given other arguments than the first are refused (shard_files.hpp).
#pragma once
#include <algorithm>
#include <bit>
#include <filesystem>
#include <vector>

#include "voxray/world/build/shard_files.hpp"
#include "voxray/world/build/shard_plan.hpp"
#include "voxray/world/build/world_build.hpp"

namespace voxray {

namespace sharded_build_detail {

inline void check_shard(world_shard s) {
    if (s.count == 0 || s.index >= s.count)
        fail("world build: shard ", s.index, " of ", s.count, " does not exist (K/N needs N >= 1 and K in [0, N))");
}

template <class Source>
shard_plan plan_of(const Source& source, const world_build_options& o, unsigned shards, int split_lod) {
    return {source.hash(), o.chunk_bits, o.density, std::uint32_t(o.attributes), std::bit_cast<std::uint32_t>(o.colour_error),
            shards, split_lod};
}

}  // namespace sharded_build_detail

// Shard `shard.index` of `shard.count`: its units up to the split LOD, and their list.
// (build_world without a shard, world_build.hpp, builds the whole world at once.)
template <class Source>
world_build_report build_world(const Source& source, const std::filesystem::path& dir, const world_build_options& o,
                               world_shard shard) {
    sharded_build_detail::check_shard(shard);
    world_builder<Source> b(source, dir, o);
    world_build_detail::folder_lock shared(dir, true);
    std::filesystem::create_directories(shards_folder(dir));
    world_build_detail::folder_lock own(shards_folder(dir), false, shard_file(dir, shard.index, shard.count, ".lock").filename());
    b.claim_folder();
    const world_grid& g = b.header().grid;
    auto cells = source.cells(g);
    auto split = shard_split::make(cells, cell_work(source, g, cells), g.top_lod, shard.count);
    agree_on_plan(dir, sharded_build_detail::plan_of(source, o, shard.count, split.split_lod));
    auto list = shard_file(dir, shard.index, shard.count, ".vxwm");
    std::filesystem::remove(list);  // listed again once this run is done

    std::vector<glm::ivec3> mine;
    for (std::size_t u : split.share(shard.index, shard.count))
        mine.insert(mine.end(), split.units[u].cells.begin(), split.units[u].cells.end());
    std::vector<manifest_chunk> chunks;
    b.build_up_from_source(mine, split.split_lod, chunks);
    world_manifest part = b.header();
    part.chunks = std::move(chunks);
    part.sort();
    write_manifest_file(list, part);
    b.report().seconds = b.seconds();
    return b.report();
}

// The chunks every shard of the folder's plan listed, checked against this build and
// against the files they name.
inline std::vector<manifest_chunk> merge_shard_lists(const std::filesystem::path& dir, const world_manifest& header,
                                                     const shard_plan& plan, world_build_report& report) {
    std::vector<manifest_chunk> all;
    for (unsigned k = 0; k < plan.shards; ++k) {
        auto path = shard_file(dir, k, plan.shards, ".vxwm");
        if (!std::filesystem::exists(path))
            fail("world build: shard ", k, " of ", plan.shards, " has not finished (no ", path.string(), "): run it (--shard ",
                 k, "/", plan.shards, ") before the finish");
        world_manifest part = read_manifest_file(path);
        if (part.source_hash != header.source_hash)
            fail("world build: ", path.string(), " lists chunks of another build (hash ", part.source_hash, ", this one's ",
                 header.source_hash, ")");
        for (auto& c : part.chunks) {
            if (c.key.lod > plan.split_lod)
                fail("world build: ", path.string(), " lists a chunk of LOD ", c.key.lod, ", above the split LOD ", plan.split_lod);
            std::error_code ec;
            auto file = chunk_file_path(dir, c.key);
            if (std::filesystem::file_size(file, ec) != c.file_bytes || ec)
                fail("world build: ", path.string(), " lists ", file.string(), " of ", c.file_bytes, " bytes, but ",
                     ec ? "it is missing" : "its size differs", ": run shard ", k, "/", plan.shards, " again");
            auto& level = report.lods[std::size_t(c.key.lod)];
            ++level.chunks, ++level.resumed, level.voxels += c.voxel_count, level.disk_bytes += c.file_bytes;
            all.push_back(c);
        }
    }
    return all;
}

// Once every shard is done: the LODs above the split, the manifest, and DIR/shards gone.
template <class Source>
world_build_report finish_world_build(const Source& source, const std::filesystem::path& dir, const world_build_options& o) {
    world_builder<Source> b(source, dir, o);
    world_build_detail::folder_lock lock(dir);  // alone: no shard runs
    auto plan_path = shard_plan_path(dir);
    if (!std::filesystem::exists(plan_path))
        fail("world build: ", dir.string(), " has no sharded build to finish (no ", plan_path.string(), ")");
    shard_plan there = read_plan(plan_path);
    const world_grid& g = b.header().grid;
    auto cells = source.cells(g);
    int split_lod = shard_split::choose_split_lod(cells, g.top_lod, there.shards);
    agree_on_plan(dir, sharded_build_detail::plan_of(source, o, there.shards, split_lod));
    b.claim_folder();
    auto chunks = merge_shard_lists(dir, b.header(), there, b.report());
    b.build_levels_above(split_lod, g.top_lod, chunks);
    b.write_manifest_of(std::move(chunks));
    std::filesystem::remove_all(shards_folder(dir));
    b.report().seconds = b.seconds();
    return b.report();
}

}  // namespace voxray
