// Builds a world on disk chunk by chunk, so that the world never exists as one voxel set
// in memory: LOD 0 chunks from a source's voxels in their cell (world/build/model_source.hpp,
// world/build/mesh_source.hpp), then each LOD from the files of the one below (decoded, 8 at a
// time). Every chunk is one independent job (the unit a batch engine would distribute);
// jobs run on all threads; a chunk file already there with the same source hash is kept,
// so a build that was interrupted resumes where it stopped. The manifest is written last;
// then the chunk files it does not list (an earlier world's) are removed. A lock keeps a
// second build out of the folder, and a finished world of another source is replaced
// only when asked (world_build_options::replace).
//
// A source offers
//   box3i bounds() const;                                   // of its solid voxels
//   std::uint32_t hash() const;                             // of its content
//   std::vector<glm::ivec3> cells(const world_grid&) const; // the cells that may hold voxels
//   chunk_voxels voxels(const world_grid&, glm::ivec3 cell, bool colours) const;  // thread-safe
#pragma once
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <mutex>
#include <set>
#include <vector>

#include "voxray/model/build_threads.hpp"
#include "voxray/svdag/decode.hpp"
#include "voxray/world/build/chunk_dag.hpp"
#include "voxray/world/chunk_file.hpp"
#include "voxray/world/lod.hpp"
#include "voxray/world/manifest.hpp"

namespace voxray {

// Where a build is: chunks done of the LOD under way (the number of LODs is known only
// when LOD 0 is done), and the time since the build began.
struct world_build_progress {
    int lod = 0, top_lod = 0;
    std::uint64_t done = 0, total = 0;  // chunk jobs of this LOD
    double seconds = 0;
};

struct world_build_options {
    int chunk_bits = 8;
    svdag_attributes attributes = svdag_attributes::exact;
    float colour_error = 0.05f;
    int density = 2;
    unsigned threads = 0;  // 0: all hardware threads
    // Called once every chunk file is written and before the manifest is: files of the
    // caller's own (shading hints, say) go here, so that a folder with a manifest has them
    // all. A throw leaves the build unfinished (no manifest).
    std::function<void(const std::filesystem::path& dir)> before_manifest;
    // A folder that holds a finished world of another source or other options is
    // refused unless this is set; then the new world replaces it.
    bool replace = false;
    // Called after each chunk (from the build threads, one call at a time).
    std::function<void(const world_build_progress&)> progress;
};

struct world_build_report {
    struct level {
        std::uint64_t chunks = 0, voxels = 0, disk_bytes = 0, resumed = 0;
        double seconds = 0;
    };
    std::vector<level> lods;
    double seconds = 0;
    std::uint64_t cells_scanned = 0;  // LOD 0 cells the source offered
    double voxels_per_second() const { return seconds > 0 ? double(lods.empty() ? 0 : lods[0].voxels) / seconds : 0; }
    double chunks_per_second() const {
        std::uint64_t n = 0;
        for (auto& l : lods) n += l.chunks;
        return seconds > 0 ? double(n) / seconds : 0;
    }
};

namespace world_build_detail {

inline std::uint32_t options_hash(std::uint32_t source, const world_build_options& o) {
    fnv64 h;
    std::uint32_t words[5] = {source, std::uint32_t(o.chunk_bits), std::uint32_t(o.attributes), std::uint32_t(o.density), 0};
    std::memcpy(&words[4], &o.colour_error, 4);
    h.bytes(words, sizeof words);
    return std::uint32_t(h.h ^ (h.h >> 32));
}

// A chunk file from an earlier run of the same build, if one is there and sound.
inline bool resumable(const std::filesystem::path& path, std::uint32_t hash, int chunk_bits, chunk_record& out) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return false;
    try {
        out = read_chunk_file(path, chunk_bits);
        return out.source_hash == hash;
    } catch (const error&) {
        return false;  // a half-written or corrupt file: build it again
    }
}

// One build at a time in a folder: two would write the same .tmp names and mix their
// chunks. An advisory lock (flock) on a file in the folder, released when the build ends
// or its process dies.
class folder_lock {
public:
    explicit folder_lock(const std::filesystem::path& dir) {
        auto path = dir / ".voxray-build.lock";
        fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd_ < 0) fail("world build: cannot open ", path.string(), " (", std::strerror(errno), ")");
        if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
            int e = errno;
            ::close(fd_);
            if (e == EWOULDBLOCK)
                fail("world build: ", dir.string(), " is being built by another process (it holds ", path.string(), ")");
            fail("world build: cannot lock ", path.string(), " (", std::strerror(e), ")");
        }
    }
    ~folder_lock() { ::close(fd_); }
    folder_lock(const folder_lock&) = delete;
    folder_lock& operator=(const folder_lock&) = delete;

private:
    int fd_ = -1;
};

// Chunk files (and .tmp files of killed writes) the manifest does not list: what an
// earlier world in the folder left. Removed once the new manifest is in place.
inline void remove_unlisted_chunks(const std::filesystem::path& dir, const world_manifest& m) {
    std::error_code ec;
    for (int lod = 0; lod <= chunk_max_lod; ++lod) {
        auto folder = dir / ("lod" + std::to_string(lod));
        if (!std::filesystem::is_directory(folder, ec)) continue;
        for (auto& entry : std::filesystem::directory_iterator(folder, ec)) {
            auto name = entry.path().filename().string();
            bool chunk = name.ends_with(".vxck"), tmp = name.ends_with(".vxck.tmp");
            if (!chunk && !tmp) continue;  // not ours
            glm::ivec3 cell;
            bool listed = chunk && std::sscanf(name.c_str(), "%d_%d_%d.vxck", &cell.x, &cell.y, &cell.z) == 3 &&
                          m.find({lod, cell}) && chunk_file_path(dir, {lod, cell}) == entry.path();
            if (!listed) std::filesystem::remove(entry.path(), ec);
        }
        if (std::filesystem::is_empty(folder, ec)) std::filesystem::remove(folder, ec);
    }
}

}  // namespace world_build_detail

template <class Source>
world_build_report build_world(const Source& source, const std::filesystem::path& dir, const world_build_options& o) {
    using namespace world_build_detail;
    // An empty path would name the current folder's files (and remove its manifest).
    if (dir.empty()) fail("world build: the output folder's path is empty");
    auto start = std::chrono::steady_clock::now();
    world_manifest m;
    m.bounds = source.bounds();
    m.grid = world_grid::fit(m.bounds, o.chunk_bits);
    m.attributes = o.attributes;
    m.colour_error = o.colour_error;
    m.density = o.density;
    m.source_hash = options_hash(source.hash(), o);
    if (o.density < 1 || o.density > 8) fail("world build: density ", o.density, " is outside [1, 8]");
    bool colours = o.attributes == svdag_attributes::colour_blocks;
    chunk_dag_options dag{o.attributes, o.colour_error};
    std::filesystem::create_directories(dir);
    folder_lock lock(dir);
    if (!o.replace && std::filesystem::exists(manifest_path(dir))) {
        std::uint32_t there = 0;
        try {
            there = read_manifest(dir).source_hash;
        } catch (const error&) {
            there = ~m.source_hash;  // unreadable: treat as another world
        }
        if (there != m.source_hash)
            fail("world build: ", dir.string(), " holds another world (source hash ", there, ", this build's ", m.source_hash,
                 "): build into another folder, or replace it");
    }
    std::filesystem::remove(manifest_path(dir));  // an unfinished build has none

    world_build_report report;
    std::mutex mutex;  // guards m.chunks and the report while jobs run
    // Runs job(key) for every key on all threads; a job returns its chunk (empty: no file).
    auto run_level = [&](int lod, const std::vector<glm::ivec3>& cells, auto&& make) {
        auto level_start = std::chrono::steady_clock::now();
        world_build_report::level stats;
        std::atomic<std::size_t> next{0};
        std::uint64_t done = 0;
        unsigned threads = resolve_build_threads(o.threads, cells.size());
        run_build_threads(threads, [&](unsigned) {
            for (std::size_t i; (i = next.fetch_add(1)) < cells.size();) {
                chunk_key key{lod, cells[i]};
                auto path = chunk_file_path(dir, key);
                chunk_record c;
                bool resumed = resumable(path, m.source_hash, o.chunk_bits, c);
                if (!resumed) {
                    c = make(key);
                    c.source_hash = m.source_hash;
                }
                std::uint64_t bytes = 0;
                if (!c.empty()) {
                    if (!resumed) write_chunk_file(path, c);
                    bytes = std::filesystem::file_size(path);
                }
                std::lock_guard lock(mutex);
                if (o.progress)
                    o.progress({lod, m.grid.top_lod, ++done, cells.size(),
                                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()});
                if (c.empty()) continue;
                m.chunks.push_back({key, c.voxel_count, bytes});
                ++stats.chunks;
                stats.voxels += c.voxel_count;
                stats.disk_bytes += bytes;
                stats.resumed += resumed;
            }
        });
        stats.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - level_start).count();
        report.lods.push_back(stats);
    };

    // LOD 0 from the source.
    auto cells = source.cells(m.grid);
    report.cells_scanned = cells.size();
    run_level(0, cells, [&](chunk_key key) { return build_chunk(source.voxels(m.grid, key.cell, colours), key, o.chunk_bits, dag); });

    // LOD n from the files of LOD n - 1.
    for (int lod = 1; lod <= m.grid.top_lod; ++lod) {
        std::set<glm::ivec3, ivec3_less> parents, below;  // `below`: this build's LOD n - 1 chunks
        for (auto& c : m.chunks)
            if (c.key.lod == lod - 1) parents.insert(c.key.cell >> 1), below.insert(c.key.cell);
        std::vector<glm::ivec3> list(parents.begin(), parents.end());
        run_level(lod, list, [&](chunk_key key) {
            std::array<chunk_voxels, 8> children;
            std::array<const chunk_voxels*, 8> present{};
            for (int o8 = 0; o8 < 8; ++o8) {
                chunk_key child{lod - 1, key.cell * 2 + glm::ivec3(o8 & 1, (o8 >> 1) & 1, o8 >> 2)};
                if (!below.count(child.cell)) continue;
                chunk_record c = read_chunk_file(chunk_file_path(dir, child), o.chunk_bits);
                for (auto& v : decode_svdag(c.dag)) {
                    children[std::size_t(o8)].keys.push_back(chunk_voxels::key(v.position));
                    children[std::size_t(o8)].values.push_back(v.attribute);
                }
                children[std::size_t(o8)].sort();
                present[std::size_t(o8)] = &children[std::size_t(o8)];
            }
            return build_chunk(downsample(present, o.chunk_bits, o.density, colours), key, o.chunk_bits, dag);
        });
    }
    m.sort();
    if (o.before_manifest) o.before_manifest(dir);
    write_manifest(dir, m);
    remove_unlisted_chunks(dir, m);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
}

}  // namespace voxray
