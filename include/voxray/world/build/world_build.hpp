// Builds a world on disk chunk by chunk, so that the world never exists as one voxel set
// in memory: LOD 0 chunks from a source's voxels in their cell (world/build/model_source.hpp,
// world/build/mesh_source.hpp), then each LOD from the files of the one below (decoded, 8 at a
// time). Every chunk is one independent job (the unit a batch engine would distribute);
// jobs run on all threads; a chunk file already there with the same source hash is kept,
// so a build that was interrupted resumes where it stopped. The manifest is written last;
// then the chunk files it does not list (an earlier world's) are removed. A lock keeps a
// second build out of the folder, and a finished world of another source is replaced
// only when asked (world_build_options::replace). The same steps (world_builder) serve
// builds shared among processes: world/build/sharded_build.hpp, voxray/mpi/world_build.hpp.
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
#include <span>
#include <vector>

#include "voxray/model/build_threads.hpp"
#include "voxray/svdag/decode.hpp"
#include "voxray/world/build/chunk_dag.hpp"
#include "voxray/world/build/shard_files.hpp"
#include "voxray/world/chunk_file.hpp"
#include "voxray/world/lod.hpp"
#include "voxray/world/manifest.hpp"

namespace voxray {

// Where a build is: chunks done of the LOD under way (the number of LODs is known only
// when LOD 0 is done), and the time since the build began; and the chunk job just done:
// its key, its time and its voxels (what a scheduling study needs).
struct world_build_progress {
    int lod = 0, top_lod = 0;
    std::uint64_t done = 0, total = 0;  // chunk jobs of this LOD
    double seconds = 0;
    chunk_key chunk;
    double chunk_seconds = 0;  // making it (reading and writing files included); 0 when resumed
    std::uint64_t chunk_voxels = 0;
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
// or its process dies. The shards of one sharded build share the folder's lock (each
// holds its own shard's exclusively); a whole build and the finish hold it alone.
class folder_lock {
public:
    explicit folder_lock(const std::filesystem::path& dir, bool shared = false,
                         const std::filesystem::path& file = ".voxray-build.lock") {
        auto path = dir / file;
        fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
        if (fd_ < 0) fail("world build: cannot open ", path.string(), " (", std::strerror(errno), ")");
        if (::flock(fd_, (shared ? LOCK_SH : LOCK_EX) | LOCK_NB) != 0) {
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

// The source hash a build of a source of hash `source` with the options `m` records would
// write in its manifest: what says whether a world was built from a given source.
inline std::uint32_t world_source_hash(std::uint32_t source, const world_manifest& m) {
    world_build_options o;
    o.chunk_bits = m.grid.chunk_bits, o.attributes = m.attributes, o.colour_error = m.colour_error;
    o.density = m.density;
    return world_build_detail::options_hash(source, o);
}

// The steps of a build, shared by the whole build (build_world below) and the sharded
// one (world/build/sharded_build.hpp): the world's header from the source and options,
// chunk levels built on all threads, and the manifest.
template <class Source>
class world_builder {
public:
    world_builder(const Source& source, const std::filesystem::path& dir, const world_build_options& o)
        : source_(source), dir_(dir), o_(o), dag_{o.attributes, o.colour_error} {
        // An empty path would name the current folder's files (and remove its manifest).
        if (dir.empty()) fail("world build: the output folder's path is empty");
        if (o.density < 1 || o.density > 8) fail("world build: density ", o.density, " is outside [1, 8]");
        m_.bounds = source.bounds();
        m_.grid = world_grid::fit(m_.bounds, o.chunk_bits);
        m_.attributes = o.attributes;
        m_.colour_error = o.colour_error;
        m_.density = o.density;
        m_.source_hash = world_build_detail::options_hash(source.hash(), o);
        report_.lods.resize(std::size_t(m_.grid.top_lod) + 1);
        std::filesystem::create_directories(dir);
    }

    const world_manifest& header() const { return m_; }
    world_build_report& report() { return report_; }

    // A finished world of another source or options is kept unless o.replace; a folder
    // being built has no manifest.
    void claim_folder() {
        if (!o_.replace && std::filesystem::exists(manifest_path(dir_))) {
            std::uint32_t there = 0;
            try {
                there = read_manifest(dir_).source_hash;
            } catch (const error&) {
                there = ~m_.source_hash;  // unreadable: treat as another world
            }
            if (there != m_.source_hash)
                fail("world build: ", dir_.string(), " holds another world (source hash ", there, ", this build's ",
                     m_.source_hash, "): build into another folder, or replace it");
        }
        std::filesystem::remove(manifest_path(dir_));
    }

    // The LOD-0 chunks of `cells` from the source, then level by level up to `top` the
    // chunks above them (`cells` must hold every LOD-0 cell under those). Appends the
    // non-empty ones to `out`.
    void build_up_from_source(const std::vector<glm::ivec3>& cells, int top, std::vector<manifest_chunk>& out) {
        bool colours = o_.attributes == svdag_attributes::colour_blocks;
        report_.cells_scanned += cells.size();
        std::size_t first = out.size();
        run_level(0, cells, out, [&](chunk_key key) {
            return build_chunk(source_.voxels(m_.grid, key.cell, colours), key, o_.chunk_bits, dag_);
        });
        build_levels_above(0, top, out, first);
    }

    // Levels from + 1 .. top from the chunk files of the levels below; out[first..] must
    // hold every chunk of LOD `from` under what is built.
    void build_levels_above(int from, int top, std::vector<manifest_chunk>& out, std::size_t first = 0) {
        for (int lod = from + 1; lod <= top; ++lod) {
            auto level = level_above(std::span(out).subspan(first), lod);
            build_level_from_below(lod, level.cells, level.below, out);
        }
    }

    // What LOD `lod` is made from: its cells (the parents of the LOD n - 1 chunks among
    // `chunks`, sorted) and those children.
    struct level_inputs {
        std::vector<glm::ivec3> cells;
        std::set<glm::ivec3, ivec3_less> below;
    };
    static level_inputs level_above(std::span<const manifest_chunk> chunks, int lod) {
        level_inputs in;
        std::set<glm::ivec3, ivec3_less> parents;
        for (auto& c : chunks)
            if (c.key.lod == lod - 1) parents.insert(c.key.cell >> 1), in.below.insert(c.key.cell);
        in.cells.assign(parents.begin(), parents.end());
        return in;
    }

    // The chunks of LOD `lod` at `cells`, each from the files of its children that
    // `below` (the LOD n - 1 chunks there are) holds. Appends the non-empty ones to `out`.
    void build_level_from_below(int lod, const std::vector<glm::ivec3>& cells, const std::set<glm::ivec3, ivec3_less>& below,
                                std::vector<manifest_chunk>& out) {
        run_level(lod, cells, out, [&](chunk_key key) { return downsampled(key, below); });
    }

    // The manifest of `chunks`, then the removal of what it does not list.
    void write_manifest_of(std::vector<manifest_chunk> chunks) {
        m_.chunks = std::move(chunks);
        m_.sort();
        if (o_.before_manifest) o_.before_manifest(dir_);
        write_manifest(dir_, m_);
        world_build_detail::remove_unlisted_chunks(dir_, m_);
    }

    double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }

private:
    // Runs make(key) for every cell of the level on all threads; a job returns its chunk
    // (empty: no file); a sound file of this build already there is kept.
    template <class Make>
    void run_level(int lod, const std::vector<glm::ivec3>& cells, std::vector<manifest_chunk>& out, Make&& make) {
        auto level_start = std::chrono::steady_clock::now();
        auto& stats = report_.lods[std::size_t(lod)];
        std::mutex mutex;  // guards `out`, the stats and the progress calls
        std::atomic<std::size_t> next{0};
        std::uint64_t done = 0;
        unsigned threads = resolve_build_threads(o_.threads, cells.size());
        run_build_threads(threads, [&](unsigned) {
            for (std::size_t i; (i = next.fetch_add(1)) < cells.size();) {
                chunk_key key{lod, cells[i]};
                auto path = chunk_file_path(dir_, key);
                chunk_record c;
                auto job_start = std::chrono::steady_clock::now();
                bool resumed = world_build_detail::resumable(path, m_.source_hash, o_.chunk_bits, c);
                if (!resumed) {
                    c = make(key);
                    c.source_hash = m_.source_hash;
                }
                std::uint64_t bytes = 0;
                if (!c.empty()) {
                    if (!resumed) write_chunk_file(path, c);
                    bytes = std::filesystem::file_size(path);
                }
                double job = resumed ? 0 : std::chrono::duration<double>(std::chrono::steady_clock::now() - job_start).count();
                std::lock_guard lock(mutex);
                if (o_.progress) o_.progress({lod, m_.grid.top_lod, ++done, cells.size(), seconds(), key, job, c.voxel_count});
                if (c.empty()) continue;
                out.push_back({key, c.voxel_count, bytes});
                ++stats.chunks;
                stats.voxels += c.voxel_count;
                stats.disk_bytes += bytes;
                stats.resumed += resumed;
            }
        });
        stats.seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - level_start).count();
    }

    // A chunk of LOD n from its (up to 8) children's files.
    chunk_record downsampled(chunk_key key, const std::set<glm::ivec3, ivec3_less>& below) const {
        std::array<chunk_voxels, 8> children;
        std::array<const chunk_voxels*, 8> present{};
        for (int o8 = 0; o8 < 8; ++o8) {
            chunk_key child{key.lod - 1, key.cell * 2 + glm::ivec3(o8 & 1, (o8 >> 1) & 1, o8 >> 2)};
            if (!below.count(child.cell)) continue;
            chunk_record c = read_chunk_file(chunk_file_path(dir_, child), o_.chunk_bits);
            for (auto& v : decode_svdag(c.dag)) {
                children[std::size_t(o8)].keys.push_back(chunk_voxels::key(v.position));
                children[std::size_t(o8)].values.push_back(v.attribute);
            }
            children[std::size_t(o8)].sort();
            present[std::size_t(o8)] = &children[std::size_t(o8)];
        }
        bool colours = o_.attributes == svdag_attributes::colour_blocks;
        return build_chunk(downsample(present, o_.chunk_bits, o_.density, colours), key, o_.chunk_bits, dag_);
    }

    const Source& source_;
    std::filesystem::path dir_;
    const world_build_options& o_;
    chunk_dag_options dag_;
    world_manifest m_;
    world_build_report report_;
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// The whole build in this process.
template <class Source>
world_build_report build_world(const Source& source, const std::filesystem::path& dir, const world_build_options& o) {
    world_builder<Source> b(source, dir, o);
    world_build_detail::folder_lock lock(dir);
    b.claim_folder();
    std::filesystem::remove_all(shards_folder(dir));  // a sharded build's leftovers: this build replaces it
    std::vector<manifest_chunk> chunks;
    b.build_up_from_source(source.cells(b.header().grid), b.header().grid.top_lod, chunks);
    b.write_manifest_of(std::move(chunks));
    b.report().seconds = b.seconds();
    return b.report();
}

}  // namespace voxray
