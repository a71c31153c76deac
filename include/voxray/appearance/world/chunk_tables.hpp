// Appearance tables for every chunk of a world on disk, every LOD (issue 25, item 6), built
// out of core like the geometry (world/build/world_build.hpp): one chunk at a time, each
// table a file beside the chunk files, so that no level's tables are ever in memory at once.
//   LOD 0   from the original triangles (precompute.hpp's build_table), the chunk's voxels
//           taken in the world's voxel space and the rows moved to the chunk's own voxels;
//   LOD n   re-sampled through the compositing walk (resample.hpp) from the (up to 8)
//           chunks of LOD n - 1 below it, placed side by side (placed_walker.hpp) and each
//           walked through its own DAG (the chunk file's) and table (the file written before).
// A chunk's rows are its DAG's voxels, the world's own LOD rule (world/lod.hpp) included,
// so the walk of a chunk is the walk of the chunk file as it is.
//
//   dir/appearance/<set>/lod<n>/<x>_<y>_<z>.vxap    (a set: one chain of tables, e.g. "compact")
//   dir/appearance/<set>/made_with.txt               what they were made with (set_stamp)
//
// A build that was stopped resumes like the geometry's: where the set's stamp matches this
// build's, every chunk whose table file is there and sound (it loads, of the expected kind,
// its rows the chunk's voxels, and no child of it made again) is kept; a stamp that differs
// (other options, another world) clears the set first.
// A world and its LOD cut walked with them: chunk_walker_of, cut_walker.
#pragma once
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <memory>
#include <set>
#include <span>
#include <string>
#include <vector>

#if !defined(VOXRAY_LINKED_CPU)
#error "voxray/appearance/world/chunk_tables.hpp needs voxray::cpu (chunks are walked on its scalar lanes): link it"
#endif
#include "voxray/appearance/precompute.hpp"
#include "voxray/appearance/resample.hpp"
#include "voxray/appearance/table_file.hpp"
#include "voxray/appearance/world/placed_walker.hpp"
#include "voxray/cpu/appearance_walk.hpp"
#include "voxray/svdag/decode.hpp"
#include "voxray/svdag/svdag.hpp"
#include "voxray/world/build/mesh_source.hpp"
#include "voxray/world/build/world_build.hpp"
#include "voxray/world/manifest.hpp"

namespace voxray::appearance {

// A chunk walked through its own DAG and table.
using chunk_walker = appearance_walker<kernels::svdag_kernel>;

struct chunk_tables_options {
    std::string set = "compact";                   // the folder of this chain of tables
    record_kind finest = record_kind::compact;     // LOD 0, from the triangles
    record_kind coarser = record_kind::compact;    // LOD 1 on, each from the level below
    std::string finest_from;                       // LOD 0's tables copied from this set, not made
    sampling_options sampling{};
    unsigned opacity_strata = 2;
    unsigned threads = 0;                          // 0: every hardware thread
    std::function<void(const chunk_key&, const precompute_stats&)> progress;  // after each chunk
};

struct chunk_tables_report {
    std::vector<precompute_stats> lods;  // per LOD: voxels, rays, hits and seconds of the tables made
    std::uint64_t resumed = 0;           // chunks whose table an earlier run made, kept
    double seconds = 0;
};

// A set's name is one folder of dir/appearance: an error otherwise (checked by
// build_chunk_tables, and by callers that want to know before a long world build).
inline void check_set_name(const std::string& set) {
    if (set.empty() || set.find_first_of("/\\") != std::string::npos || set == "." || set == "..")
        fail("appearance chunk tables: the set's name \"", set, "\" must be one folder name");
}

inline std::filesystem::path chunk_table_path(const std::filesystem::path& dir, const std::string& set,
                                              const chunk_key& k) {
    return dir / "appearance" / set / ("lod" + std::to_string(k.lod)) /
           (std::to_string(k.cell.x) + "_" + std::to_string(k.cell.y) + "_" + std::to_string(k.cell.z) + ".vxap");
}

// Where a chunk lies in the world's voxels.
inline piece_placement chunk_placement(const world_grid& g, const chunk_key& k) {
    return {g.origin + k.cell * (g.edge() << k.lod), 1 << k.lod, g.edge()};
}

// The table of `set` for chunk `c` (as read_listed_chunk reads it): a missing file, or a
// table of other voxels (another world's, or another build's), is an error naming the file.
inline appearance_table load_chunk_table(const std::filesystem::path& dir, const std::string& set,
                                         const chunk_record& c) {
    auto path = chunk_table_path(dir, set, c.key);
    if (!std::filesystem::exists(path))
        fail("appearance table file ", path.string(), ": missing (the chunk's table of set \"", set,
             "\": build the world's tables first)");
    appearance_table t = load_table(path);
    if (t.size() != c.voxel_count)
        fail("appearance table file ", path.string(), ": ", t.size(), " rows, but its chunk has ", c.voxel_count,
             " voxels (a table of another world?)");
    return t;
}

// The walker of a chunk the manifest lists, with its table of `set`.
inline std::shared_ptr<const chunk_walker> chunk_walker_of(const std::filesystem::path& dir, const world_manifest& m,
                                                           const std::string& set, const chunk_key& k) {
    chunk_record c = read_listed_chunk(dir, m, k);
    appearance_table t = load_chunk_table(dir, set, c);
    return std::make_shared<const chunk_walker>(std::move(c.dag), t, 1);
}

// The chunks of `cut` (a LOD selection, world/lod_select.hpp) walked as one, in world voxels.
inline placed_walker<chunk_walker> cut_walker(const std::filesystem::path& dir, const world_manifest& m,
                                              const std::string& set, std::span<const chunk_key> cut) {
    placed_walker<chunk_walker> w;
    for (const chunk_key& k : cut) w.add(chunk_placement(m.grid, k), chunk_walker_of(dir, m, set, k));
    return w;
}

namespace chunk_tables_detail {

inline std::vector<glm::ivec3> chunk_voxels_of(const chunk_record& c) {
    std::vector<glm::ivec3> out;
    out.reserve(c.voxel_count);
    for (const decoded_voxel& v : decode_svdag(c.dag)) out.push_back(v.position);
    return out;
}

// A table of voxels in the world's space moved to the chunk's own voxels. Chunk corners are
// multiples of the chunk edge (16 at least), so the ordinal order (bricks of 4) is kept.
inline void move_to_chunk(appearance_table& t, glm::ivec3 corner) {
    for (glm::ivec3& v : t.voxels) v -= corner;
    if (!std::is_sorted(t.voxels.begin(), t.voxels.end(), ordinal_less))
        fail("appearance chunk tables: a chunk corner (", corner.x, ", ", corner.y, ", ", corner.z,
             ") that is not a multiple of 4 reorders the rows");
}

inline void add_stats(precompute_stats& sum, const precompute_stats& s) {
    sum.voxels += s.voxels, sum.rays += s.rays, sum.hits += s.hits, sum.seconds += s.seconds;
}

// One line saying what a set's tables are made of and with: the world (its source hash and
// chunk count) and every option that changes a table (not the thread count: tables do not
// depend on it).
inline std::string set_stamp(const world_manifest& m, const chunk_tables_options& o) {
    return "voxray appearance set 1: world " + std::to_string(m.source_hash) + " chunks " +
           std::to_string(m.chunks.size()) + " finest " + std::to_string(int(o.finest)) + " coarser " +
           std::to_string(int(o.coarser)) + " finest_from \"" + o.finest_from + "\" rays " +
           std::to_string(o.sampling.rays) + " stratified " + std::to_string(int(o.sampling.stratified)) + " seed " +
           std::to_string(o.sampling.seed) + " opacity_strata " + std::to_string(o.opacity_strata) + "\n";
}

inline std::string read_text(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return in ? std::string(std::istreambuf_iterator<char>(in), {}) : std::string();
}

// Readies dir/appearance/<set> for a build stamped `stamp`: kept as it is when its stamp is
// the same (a resumed build), else emptied and stamped. False when nothing can be kept.
inline bool ready_set_folder(const std::filesystem::path& folder, const std::string& stamp) {
    const auto stamp_path = folder / "made_with.txt";
    if (read_text(stamp_path) == stamp) return true;
    std::filesystem::remove_all(folder);  // tables of other options: none may be taken for this build's
    std::filesystem::create_directories(folder);
    std::ofstream out(stamp_path, std::ios::binary | std::ios::trunc);
    out << stamp;
    if (!out) fail("appearance chunk tables: cannot write ", stamp_path.string());
    return false;
}

// The table an earlier run of the same build left for chunk `c`, if it is there and sound.
inline bool resumable_table(const std::filesystem::path& path, const chunk_record& c, record_kind kind,
                            appearance_table& out) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) return false;
    try {
        out = load_table(path);
    } catch (const error&) {
        return false;  // half written or damaged: make it again
    }
    if (out.kind != kind || out.shadows || out.size() != c.voxel_count) return false;
    std::vector<glm::ivec3> voxels = chunk_voxels_of(c);
    std::sort(voxels.begin(), voxels.end(), ordinal_less);  // the rows' order
    return out.voxels == voxels;
}

}  // namespace chunk_tables_detail

// The tables of every chunk of the world in `dir`, built (world/build/world_build.hpp) from
// mesh_source(mesh, resolution): a world of another mesh or resolution is an error (its
// manifest's source hash says). `scene` holds the triangles in the world's voxel space (the
// map mesh_source voxelizes with: io::make_grid_map(mesh.bounds(), resolution)).
template <class Scene>
chunk_tables_report build_chunk_tables(const Scene& scene, const io::triangle_mesh& mesh, int resolution,
                                       const std::filesystem::path& dir, const chunk_tables_options& o) {
    using namespace chunk_tables_detail;
    check_set_name(o.set);
    auto start = std::chrono::steady_clock::now();
    mesh.validate();
    const world_manifest m = read_manifest(dir);
    if (std::uint32_t built = world_source_hash(mesh_source_hash(mesh, resolution), m); built != m.source_hash)
        fail("appearance chunk tables: the world in ", dir.string(), " was not built from this mesh at resolution ",
             resolution, " (its manifest's source hash is ", m.source_hash, ", this mesh's ", built, ")");
    chunk_tables_report report;
    report.lods.resize(std::size_t(m.grid.top_lod) + 1);
    auto options_for = [&](record_kind kind) {
        return precompute_options{.kind = kind, .sampling = o.sampling, .opacity_strata = o.opacity_strata,
                                  .threads = o.threads, .light = {}};
    };
    const bool resuming = ready_set_folder(dir / "appearance" / o.set, set_stamp(m, o));
    std::set<chunk_key, chunk_key_less> made;  // tables this run made: their parents are made again too
    for (const manifest_chunk& listed : m.chunks) {  // by LOD: every child is done before its parent
        const chunk_key& k = listed.key;
        chunk_record c = read_listed_chunk(dir, m, k);
        precompute_stats stats;
        appearance_table t;
        auto path = chunk_table_path(dir, o.set, k);
        bool children_kept = true;
        for (int octant = 0; octant < 8 && k.lod > 0; ++octant) {
            glm::ivec3 step(octant & 1, (octant >> 1) & 1, octant >> 2);
            children_kept = children_kept && !made.count({k.lod - 1, k.cell * 2 + step});
        }
        if (resuming && children_kept &&
            resumable_table(path, c, k.lod == 0 ? o.finest : o.coarser, t)) {
            ++report.resumed;
            if (o.progress) o.progress(k, stats);  // nothing sampled in this run
            continue;
        }
        made.insert(k);
        if (k.lod == 0 && !o.finest_from.empty()) {
            t = load_chunk_table(dir, o.finest_from, c);
        } else if (k.lod == 0) {
            const glm::ivec3 corner = chunk_placement(m.grid, k).origin;
            std::vector<glm::ivec3> voxels = chunk_voxels_of(c);
            for (glm::ivec3& v : voxels) v += corner;
            t = build_table(triangle_surfaces{scene, mesh}, std::move(voxels), options_for(o.finest), &stats);
            move_to_chunk(t, corner);
        } else {
            // The children side by side in the finer voxels of this chunk's region, [0, 2C)^3.
            placed_walker<chunk_walker> below;
            for (int octant = 0; octant < 8; ++octant) {
                glm::ivec3 step(octant & 1, (octant >> 1) & 1, octant >> 2);
                chunk_key child{k.lod - 1, k.cell * 2 + step};
                if (m.find(child))
                    below.add({step * m.grid.edge(), 1, m.grid.edge()}, chunk_walker_of(dir, m, o.set, child));
            }
            t = resample(below, chunk_voxels_of(c), options_for(o.coarser), &stats);
        }
        std::filesystem::create_directories(path.parent_path());
        save_table(t, path);
        add_stats(report.lods[std::size_t(k.lod)], stats);
        if (o.progress) o.progress(k, stats);
    }
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return report;
}

}  // namespace voxray::appearance
