// voxray world-build / world-fly: an open world on disk, chunk by chunk, and a camera
// path through it with streaming. world-build writes the chunk files and the manifest
// (world/build/world_build.hpp) plus voxray-world.json (the scene's up axis and palette, for
// shading); world-fly streams the world along a camera path (world/stream/streamed_world.hpp),
// traces each frame on a backend (or, with --passes, renders it with the GPU-driven
// passes of world/frame/frame.hpp), and reports per frame what was resident and what it cost.
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <optional>

#include <nlohmann/json.hpp>

#include "backends.hpp"
#include "cli.hpp"
#include "engines.hpp"
#include "image_writer.hpp"
#include "output.hpp"
#include "scene.hpp"
#include "ssim.hpp"
#include "world_fly_appearance.hpp"
#include "world_meta.hpp"
#include "world_raster.hpp"
#include "voxray/gltf/coloured_mesh.hpp"
#include "voxray/io/mesh_loader.hpp"
#include "voxray/rays.hpp"
#include "voxray/world/frame/frame.hpp"
#include "voxray/world/build/mesh_source.hpp"
#include "voxray/world/build/model_source.hpp"
#include "voxray/world/stream/streamed_world.hpp"
#include "voxray/world/build/sharded_build.hpp"
#include "voxray/world/build/world_build.hpp"
#include "world_mpi.hpp"
#if VOXRAY_WITH_EMBREE
#include "voxray/appearance/world/chunk_tables.hpp"
#include "voxray/embree/triangle_scene.hpp"
#endif

namespace voxray::tool {

namespace {

using json = nlohmann::json;

double peak_rss_mib() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return double(u.ru_maxrss) / 1024.0;  // KiB on Linux
}

struct build_options {
    scene_options scene;
    std::string out, json_out, chunk_times;
    int chunk_bits = 8, density = 2;
    bool colours = false, force = false;
    std::string appearance;  // a mesh world's appearance tables: this set's name (empty: none)
    float colour_error = 0.05f;
    std::vector<int> tile{1, 1, 1};
    unsigned threads = 0;
    std::string shard, mpi_schedule = "dynamic";  // shard: "K/N" or empty
    bool finish = false;
};

// --shard K/N: share K (0-based) of N.
world_shard parse_shard(const std::string& text) {
    unsigned k = 0, n = 0;
    char slash = 0, extra = 0;
    if (std::sscanf(text.c_str(), "%u %c %u %c", &k, &slash, &n, &extra) != 3 || slash != '/' || n == 0 || k >= n ||
        text.find('-') != std::string::npos)
        fail("--shard '", text, "': expected K/N with N >= 1 and K in [0, N) (K counts from 0, as Slurm array ids do)");
    return {k, n};
}

// Progress on stderr, at most twice a second and at the end of each LOD: chunks done,
// their rate and the LOD's time to go. (The build calls it one call at a time.)
std::function<void(const world_build_progress&)> progress_printer() {
    struct state {
        double printed = -1, lod_start = 0;
        int lod = -1;
    };
    auto s = std::make_shared<state>();
    return [s](const world_build_progress& p) {
        if (p.lod != s->lod) s->lod = p.lod, s->lod_start = p.seconds;
        if (p.done != p.total && p.seconds - s->printed < 0.5) return;
        s->printed = p.seconds;
        double spent = p.seconds - s->lod_start, rate = spent > 0 ? double(p.done) / spent : 0;
        std::string to_go = rate > 0 ? std::to_string(int(double(p.total - p.done) / rate)) + " s" : "?";
        std::fprintf(stderr, "LOD %d of %d: %llu / %llu chunks, %.0f chunks/s, %s to go for this LOD, %.0f s in all%s", p.lod,
                     p.top_lod, (unsigned long long)p.done, (unsigned long long)p.total, rate, to_go.c_str(), p.seconds,
                     p.done == p.total ? "\n" : "   \r");
    };
}

// --appearance is refused before the world is built, not after: without triangles (`allowed`
// false, `instead` says what was given), without Embree, or with a set name that is not one folder.
void check_appearance_request(const build_options& o, bool allowed, const std::string& instead) {
    if (!allowed)
        fail("--appearance: tables are made from a mesh (.obj, .ply, .gltf, .glb) in a build of one process, not from ",
             instead);
#if VOXRAY_WITH_EMBREE
    appearance::check_set_name(o.appearance);
#else
    fail("world-build --appearance needs Embree (LOD 0's tables are sampled from the triangles): this build has none");
#endif
}

// --appearance: the finished world's chunk tables at every LOD, LOD 0 from the triangles and
// each coarser LOD re-sampled from the one below (appearance/world/chunk_tables.hpp).
void build_appearance_tables(const io::triangle_mesh& mesh, const build_options& o) {
#if VOXRAY_WITH_EMBREE
    embree::triangle_scene scene(mesh, io::make_grid_map(mesh.bounds(), o.scene.resolution));
    appearance::chunk_tables_options tables;
    tables.set = o.appearance, tables.threads = o.threads;
    std::fprintf(stderr, "appearance tables (%s) of every chunk at every LOD ...\n", o.appearance.c_str());
    appearance::chunk_tables_report r = appearance::build_chunk_tables(scene, mesh, o.scene.resolution, o.out, tables);
    std::uint64_t voxels = 0;
    for (const auto& lod : r.lods) voxels += lod.voxels;
    std::printf("appearance tables %s: %zu LODs, %llu voxels in %.1f s, %llu chunks' tables kept from an earlier run,"
                " in %s\n",
                o.appearance.c_str(), r.lods.size(), (unsigned long long)voxels, r.seconds,
                (unsigned long long)r.resumed,
                (std::filesystem::path(o.out) / "appearance" / o.appearance).string().c_str());
#else
    (void)mesh, (void)o;  // refused before the build (check_appearance_request)
#endif
}

int world_build(const build_options& o) {
    const std::string& spec = o.scene.scenes[0];
    // Checked before anything loads: the folder, and the report's file.
    require_writable_folder(o.out, "--out");
    if (!o.json_out.empty()) require_writable(o.json_out, "--json");
    world_build_options wo;
    wo.chunk_bits = o.chunk_bits;
    wo.density = o.density;
    wo.threads = o.threads;
    wo.attributes = o.colours ? svdag_attributes::colour_blocks : svdag_attributes::exact;
    wo.colour_error = o.colour_error;
    wo.replace = o.force;
    wo.progress = progress_printer();
    bool mesh = gltf::is_coloured_mesh_path(spec);  // .obj, .ply, .gltf, .glb: coloured where the file is
    world_build_report report;
    palette pal;
    int up_axis = 2;
    // The shading hints are written with the chunks, before the manifest: a folder whose
    // manifest is there has them (and a failed write leaves the build unfinished).
    wo.before_manifest = [&](const std::filesystem::path& dir) {
        json colours = json::array();
        for (int i = 0; i < 256; ++i) colours.push_back(pack_rgba(pal[std::uint8_t(i)].colour));
        write_file_atomically(dir / world_meta_file,
                              json{{"scene", scene_label(spec)}, {"up_axis", up_axis}, {"palette", colours}}.dump() + "\n",
                              "world-build");
    };
    // One process, a shard, the finish of shards, or one of the ranks mpirun started.
    std::optional<world_shard> shard;
    if (!o.shard.empty()) shard = parse_shard(o.shard);
    if (shard && o.finish) fail("--shard and --finish: run the shards first, then --finish alone");
    if (!o.appearance.empty())
        check_appearance_request(o, mesh && !shard && !o.finish, mesh ? "--shard or --finish" : spec);
    auto ranks = mpi_ranks::if_launched();
    if (ranks && (shard || o.finish)) fail("--shard and --finish are for separate jobs, not for ranks mpirun starts");
    if (ranks && !o.appearance.empty())
        fail("--appearance: tables are made in a build of one process, not by MPI ranks");
    bool quiet = ranks && ranks->rank() != 0;  // rank 0 speaks for all
    if (quiet) wo.progress = nullptr;
    std::optional<output_file> times;  // --chunk-times: a line a chunk job (each rank its own file)
    if (!o.chunk_times.empty()) {
        times.emplace(ranks ? o.chunk_times + ".rank" + std::to_string(ranks->rank()) : o.chunk_times, "--chunk-times");
        times->stream() << "lod\tx\ty\tz\tseconds\tvoxels\n";
        wo.progress = [&times, print = wo.progress](const world_build_progress& p) {
            times->stream() << p.chunk.lod << '\t' << p.chunk.cell.x << '\t' << p.chunk.cell.y << '\t' << p.chunk.cell.z << '\t'
                            << p.chunk_seconds << '\t' << p.chunk_voxels << '\n';
            if (print) print(p);
        };
    }
    auto build = [&](const auto& source) {
        if (ranks) return ranks->build(source, o.out, wo, o.mpi_schedule);
        if (shard) return build_world(source, o.out, wo, *shard);
        if (o.finish) return finish_world_build(source, o.out, wo);
        return build_world(source, o.out, wo);
    };
    auto start = std::chrono::steady_clock::now();
    try {
        if (mesh) {
            io::triangle_mesh m = gltf::load_coloured_mesh(spec);
            if (!quiet) std::fprintf(stderr, "building a world from %s at %d, chunk by chunk ...\n", spec.c_str(), o.scene.resolution);
            mesh_source source(m, o.scene.resolution, o.scene.max_cell_tests);
            pal = source.colours();
            up_axis = 1;
            report = build(source);
            if (!o.appearance.empty()) build_appearance_tables(m, o);
        } else {
            voxel_model model = load_scene(spec, o.scene);
            pal = model.palette();
            up_axis = model.up_axis;
            if (!quiet)
                std::fprintf(stderr, "building a world from %s tiled %d x %d x %d ...\n", spec.c_str(), o.tile[0], o.tile[1], o.tile[2]);
            report = build(model_source(model, {o.tile[0], o.tile[1], o.tile[2]}));
        }
    } catch (const error& e) {
        // A failure all ranks share: rank 0 reports it and its exit fails the job (a
        // non-zero exit here could make mpirun stop rank 0 before it prints). A rank's own
        // failure (its scene unreadable, say): it says so itself, and mpirun stops the job.
        if (quiet && mpi_ranks::failed_on_every_rank(e)) return 0;
        if (quiet) {
            std::fprintf(stderr, "voxray world-build: error on rank %d of %d: %s\n", ranks->rank(), ranks->size(), e.what());
            return 1;
        }
        throw;
    }
    if (times) times->finish();
    if (quiet) return 0;
    if (shard) {
        std::uint64_t chunks = 0;
        for (auto& l : report.lods) chunks += l.chunks;
        std::printf("shard %u of %u: %llu chunks of LODs up to the split in %.1f s (%.1f chunks/s); then --finish\n",
                    shard->index, shard->count, (unsigned long long)chunks, report.seconds, report.chunks_per_second());
        return 0;
    }
    double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    world_manifest m = read_manifest(o.out);

    glm::ivec3 e = m.bounds.extent();
    std::printf("world %s: %d x %d x %d voxels, chunks of %d^3, LODs 0..%d, %s attributes\n", o.out.c_str(), e.x, e.y, e.z,
                1 << m.grid.chunk_bits, m.grid.top_lod, o.colours ? "colour-block" : "exact");
    std::printf("%4s %10s %14s %12s %9s %8s\n", "LOD", "chunks", "voxels", "disk MiB", "seconds", "resumed");
    json lods = json::array();
    for (std::size_t n = 0; n < report.lods.size(); ++n) {
        auto& l = report.lods[n];
        std::printf("%4zu %10llu %14llu %12.2f %9.2f %8llu\n", n, (unsigned long long)l.chunks, (unsigned long long)l.voxels,
                    double(l.disk_bytes) / 1048576.0, l.seconds, (unsigned long long)l.resumed);
        lods.push_back({{"lod", n}, {"chunks", l.chunks}, {"voxels", l.voxels}, {"disk_bytes", l.disk_bytes}, {"seconds", l.seconds}, {"resumed", l.resumed}});
    }
    double rss = peak_rss_mib();
    int processes = ranks ? ranks->size() : 1;
    if (o.finish)  // the shards built (and timed) the chunks up to the split: they count as resumed here
        std::printf("%.1f s in all for the finish, peak memory %.0f MiB, %.1f MiB on disk\n", seconds, rss,
                    double(m.disk_bytes()) / 1048576.0);
    else
        std::printf("%.1f s in all (%.1f s building), %.1f M voxels/s, %.1f chunks/s on %d process%s, peak memory %.0f MiB "
                    "(this process), %.1f MiB on disk\n",
                    seconds, report.seconds, report.voxels_per_second() / 1e6, report.chunks_per_second(), processes,
                    processes == 1 ? "" : "es", rss, double(m.disk_bytes()) / 1048576.0);
    if (!o.json_out.empty()) {
        output_file out(o.json_out, "--json", std::ios::app);
        out.stream() << json{{"scene", scene_label(spec)}, {"resolution", mesh ? o.scene.resolution : 0}, {"tile", o.tile},
                    {"extent", {e.x, e.y, e.z}}, {"chunk_bits", m.grid.chunk_bits}, {"top_lod", m.grid.top_lod},
                    {"colours", o.colours}, {"seconds", seconds}, {"build_seconds", report.seconds},
                    {"voxels_per_second", report.voxels_per_second()}, {"chunks_per_second", report.chunks_per_second()},
                    {"peak_rss_mib", rss}, {"disk_bytes", m.disk_bytes()}, {"lods", lods}, {"processes", processes},
                    {"mpi_schedule", ranks ? o.mpi_schedule : ""}, {"finish", o.finish}}
                   .dump()
            << "\n";
        out.finish();
    }
    return 0;
}

struct fly_options {
    std::string dir, backend = "cpu", png_dir, json_out;
    int frames = 24, width = 640, height = 360;
    double factor = 2.0, budget_mib = 1024;
    bool lod0 = false, passes = false, raster = false;
    float lod_bias = 8.0f;  // --raster: POP inside each chunk, t = log2(distance in its cells) - bias
    std::string appearance;  // a set of the world's appearance tables, walked beside the traced frame
};

// The camera path: along the world's longest horizontal axis, a third of the way up,
// from one end to the other, looking ahead and sweeping a little left and right.
camera path_camera(const box3i& b, int up_axis, int frame, int frames) {
    int a = (up_axis + 1) % 3, c = (up_axis + 2) % 3;
    glm::vec3 lo(b.min), hi(b.max), size = hi - lo;
    if (size[c] > size[a]) std::swap(a, c);
    float s = frames > 1 ? float(frame) / float(frames - 1) : 0.5f;
    glm::vec3 eye = lo + size * 0.5f;
    eye[a] = lo[a] + size[a] * (0.08f + 0.84f * s);
    eye[up_axis] = lo[up_axis] + size[up_axis] * 0.33f;
    glm::vec3 ahead(0.0f), side(0.0f), up(0.0f);
    ahead[a] = 1.0f, side[c] = 1.0f, up[up_axis] = 1.0f;
    float yaw = 0.5f * std::sin(6.2831853f * s);
    glm::vec3 target = eye + (std::cos(yaw) * ahead + std::sin(yaw) * side) * size[a] * 0.25f - up * size[up_axis] * 0.05f;
    return look_at(eye, target, 60.0f, up);
}

// Host memory a pixel of a flight takes: its ray, hit, shadow ray and shadow hit, its
// RGBA and (with --passes) its 64-bit visibility word.
constexpr std::uint64_t fly_bytes_per_pixel = 2 * sizeof(ray) + 2 * sizeof(hit) + 4 + 8;

template <class Backend>
int fly(const fly_options& o) {
    // Checked before the world opens: what a frame needs, and where its output goes.
    require_memory(fly_bytes_per_pixel * std::uint64_t(o.width) * std::uint64_t(o.height),
                   "world-fly " + std::to_string(o.width) + " x " + std::to_string(o.height) + " (" +
                       std::to_string(fly_bytes_per_pixel) + " bytes a pixel)");
    if (!o.json_out.empty()) require_writable(o.json_out, "--json");
    if (!o.png_dir.empty()) require_writable_folder(o.png_dir, "--png-dir");
    if (o.raster && o.passes)
        fail("--raster compares with the traced frame, which --passes does not make: use one of them");
    if (!o.appearance.empty() && o.passes)
        fail("--appearance walks the traced frame's rays, which --passes does not make: use one of them");
    residency_options ro;
    ro.streaming_factor = o.lod0 ? 1e9 : o.factor;
    ro.budget_bytes = o.lod0 ? std::uint64_t(-1) / 2 : std::uint64_t(o.budget_mib * 1048576.0);
    streamed_world world(o.dir, ro);  // fails first, naming the manifest, on a folder without a world
    // Shading hints from world-build (a world built through the library has none: Z up, grey).
    world_meta meta = read_world_meta(o.dir);
    const int up_axis = meta.up_axis;
    const palette& pal = meta.colours;
    const world_manifest& m = world.manifest();
    bool colours = m.attributes == svdag_attributes::colour_blocks;
    tracer<Backend, streamed_world> t(world);
    std::optional<output_file> out;
    if (!o.json_out.empty()) out.emplace(o.json_out, "--json", std::ios::app);
    double disk = double(m.disk_bytes());
    std::optional<world_frame<Backend, streamed_world>> passes;  // --passes: the GPU-driven frame
    if (o.passes) passes.emplace(t);
    std::optional<world_raster> raster;  // --raster: the shown chunks meshed and drawn beside the traced frame
    if (o.raster) raster.emplace(pal, colours, up_axis, o.lod_bias);
    std::optional<fly_appearance> filtered;  // --appearance: the cut walked through its tables
    if (!o.appearance.empty()) filtered.emplace(o.dir, m, o.appearance, 0);
    float far_depth = glm::length(glm::vec3(m.bounds.extent())) * 1.5f + 64.0f;
    if (o.passes)
        std::printf("%5s %9s %9s %9s %9s %9s %9s %9s %7s %7s %8s %12s %8s\n", "frame", "update ms", "upload ms", "select ms",
                    "march ms", "hi-z ms", "resolve", "frame ms", "visible", "pairs", "chunks", "resident MiB", "of disk");
    else
        std::printf("%5s %9s %9s %9s %10s %8s %12s %10s %8s\n", "frame", "update ms", "upload ms", "trace ms", "sent KiB",
                    "chunks", "resident MiB", "device MiB", "of disk");
    double peak_share = 0;
    for (int f = 0; f < o.frames; ++f) {
        camera cam = path_camera(m.bounds, up_axis, f, o.frames);
        auto t0 = std::chrono::steady_clock::now();
        world.update(glm::dvec3(cam.position), true);
        auto t1 = std::chrono::steady_clock::now();
        t.update(world);
        auto t2 = std::chrono::steady_clock::now();
        auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
        glm::vec3 sun = sun_direction(up_axis);
        std::vector<ray> rays;
        std::vector<hit> hits, shadow;
        frame_stats fs;
        if (o.passes) {
            frame_view view(cam, o.width, o.height, far_depth);
            fs = passes->render(view, world.blob());
            if (!o.png_dir.empty()) {
                // Read back only for the PNG: the visibility word's face and the resolved
                // attribute are all shading needs; the pixels' rays give the sky.
                auto vis = passes->visibility();
                auto materials = passes->materials();
                hits.resize(materials.size());
                for (int y = 0; y < o.height; ++y)
                    for (int x = 0; x < o.width; ++x) rays.push_back(world_frame<Backend, streamed_world>::pixel_ray(view, x, y));
                for (std::size_t i = 0; i < hits.size(); ++i) {
                    if (!(vis[2 * i] | vis[2 * i + 1])) continue;
                    hits[i].status = VX_STATUS_HIT;
                    hits[i].normal = static_cast<face>(VX_WF_FACE(vis[2 * i + 1]));
                    hits[i].material = materials[i];
                }
                shadow.resize(hits.size());  // the passes make primary visibility only: no shadows
            }
        } else {
            rays = primary_rays(cam, o.width, o.height);
            hits.resize(rays.size()), shadow.resize(rays.size());
            t.closest_hit(rays, hits);
            auto shadow_set = shadow_rays(rays, hits, sun);
            t.any_hit(shadow_set, shadow);
        }
        auto t3 = std::chrono::steady_clock::now();
        auto s = world.residency().stats();
        double share = double(s.resident_bytes) / disk;
        peak_share = std::max(peak_share, share);
        auto pass_ms = [&](std::initializer_list<frame_stats::step> steps) {
            double sum = 0;
            for (auto k : steps) sum += fs.ms[k];
            return sum;
        };
        if (o.passes)
            std::printf("%5d %9.1f %9.1f %9.1f %9.1f %9.1f %9.1f %9.1f %7u %7u %8llu %12.2f %7.1f%%\n", f, ms(t0, t1),
                        ms(t1, t2), pass_ms({frame_stats::select_chunks, frame_stats::select_tiles, frame_stats::select_again}),
                        pass_ms({frame_stats::march, frame_stats::march_again}),
                        pass_ms({frame_stats::build_hiz, frame_stats::build_hiz_again}),
                        pass_ms({frame_stats::clear, frame_stats::resolve}), fs.total_ms(),
                        fs.visible_chunks, fs.pairs + fs.pairs_again, (unsigned long long)s.resident_chunks,
                        double(s.resident_bytes) / 1048576.0, 100.0 * share);
        else
            std::printf("%5d %9.1f %9.1f %9.1f %10.1f %8llu %12.2f %10.2f %7.1f%%\n", f, ms(t0, t1), ms(t1, t2), ms(t2, t3),
                        double(t.bytes_uploaded_last_update()) / 1024.0, (unsigned long long)s.resident_chunks,
                        double(s.resident_bytes) / 1048576.0, double(world.bytes()) / 1048576.0, 100.0 * share);
        auto picture = [&](bool shadows) {
            std::vector<std::uint8_t> rgb(rays.size() * 3);
            for (std::size_t i = 0; i < rays.size(); ++i) {
                glm::vec3 a = colours ? albedo_rgba8(hits[i]) : albedo(pal, hits[i]);
                bool dark = shadows && shadow[i].is_hit();
                glm::vec3 c = hits[i].is_hit() ? shade(a, hits[i], sun, dark) : sky(rays[i].direction, up_axis);
                auto px = to_srgb8(c);
                std::copy(px.begin(), px.end(), rgb.begin() + std::ptrdiff_t(i * 3));
            }
            return rgb;
        };
        auto png = [&](const char* pattern, int width, const std::vector<std::uint8_t>& rgb) {
            char name[48];
            std::snprintf(name, sizeof name, pattern, f);
            write_image((std::filesystem::path(o.png_dir) / name).string(), width, o.height, rgb);
        };
        if (!o.png_dir.empty()) png("frame_%03d.png", o.width, picture(true));
        json appearance_line;
        if (filtered) {
            fly_appearance::frame a = filtered->walk(rays, glm::dvec3(cam.position), ro.streaming_factor, sun, up_axis);
            std::printf("      appearance %s: %zu chunks in the cut (%zu read in %.1f ms), walked in %.1f ms, "
                        "%.2f voxels blended a ray\n",
                        o.appearance.c_str(), a.chunks, a.read, a.read_ms, a.walk_ms, a.visits);
            appearance_line = {{"set", o.appearance}, {"chunks", a.chunks},   {"chunks_read", a.read},
                               {"read_ms", a.read_ms}, {"walk_ms", a.walk_ms}, {"visits_per_ray", a.visits}};
            if (!o.png_dir.empty()) png("appearance_%03d.png", o.width, a.rgb);
        }
        json raster_line;
        if (raster) {
            // The traced frame lit as the raster path lights (no shadows), for SSIM.
            world_raster_frame r = raster->draw(world, cam, o.width, o.height);
            std::vector<std::uint8_t> traced = picture(false);
            double ssim = ssim_rgb8(r.rgb, traced, o.width, o.height);
            // Rays that start in a solid voxel or on its side (t = 0): the traced frame shows
            // that voxel, where the raster path sees past faces through the eye.
            std::size_t inside = 0;
            for (const hit& h : hits) inside += h.is_hit() && h.t <= 0.0f;
            double inside_share = hits.empty() ? 0.0 : double(inside) / double(hits.size());
            std::printf("      raster: %llu quads from %llu chunks (%llu meshed in %.1f ms), drawn in %.1f ms; "
                        "SSIM %.4f against the traced frame (%.1f%% of its rays start in or on a solid voxel)\n",
                        (unsigned long long)r.quads, (unsigned long long)r.chunks_shown,
                        (unsigned long long)r.chunks_meshed, r.mesh_ms, r.draw_ms, ssim, 100.0 * inside_share);
            raster_line = {{"quads", r.quads}, {"chunks_meshed", r.chunks_meshed}, {"mesh_ms", r.mesh_ms},
                           {"draw_ms", r.draw_ms}, {"ssim", ssim}, {"lod_bias", o.lod_bias},
                           {"rays_starting_in_a_voxel", inside_share}};
            if (!o.png_dir.empty()) {
                // Side by side: the raster frame, then the traced one.
                std::vector<std::uint8_t> both(traced.size() * 2);
                std::size_t row = std::size_t(o.width) * 3;
                for (int y = 0; y < o.height; ++y) {
                    std::copy_n(r.rgb.begin() + std::ptrdiff_t(y * row), row,
                                both.begin() + std::ptrdiff_t(2 * y * row));
                    std::copy_n(traced.begin() + std::ptrdiff_t(y * row), row,
                                both.begin() + std::ptrdiff_t((2 * y + 1) * row));
                }
                png("raster_and_traced_%03d.png", 2 * o.width, both);
            }
        }
        if (out) {
            json line{{"world", o.dir}, {"backend", Backend::name}, {"factor", o.lod0 ? 0.0 : o.factor}, {"lod0", o.lod0},
                      {"frame", f}, {"update_ms", ms(t0, t1)}, {"upload_ms", ms(t1, t2)}, {"trace_ms", ms(t2, t3)},
                      {"sent_bytes", t.bytes_uploaded_last_update()}, {"resident_chunks", s.resident_chunks},
                      {"resident_bytes", s.resident_bytes}, {"device_bytes", world.bytes()}, {"disk_bytes", m.disk_bytes()},
                      {"failures", s.failures}};
            if (raster) line["raster"] = raster_line;
            if (filtered) line["appearance"] = appearance_line;
            if (o.passes) {
                json per_pass = json::object();
                for (std::size_t k = 0; k < fs.ms.size(); ++k) per_pass[std::string(frame_stats::pass_names[k])] = fs.ms[k];
                line["passes"] = per_pass;
                line["visible_chunks"] = fs.visible_chunks;
                line["pairs"] = fs.pairs;
                line["pairs_again"] = fs.pairs_again;
                line["frame_buffer_bytes"] = fs.frame_bytes;
                line["width"] = o.width;
                line["height"] = o.height;
            }
            out->stream() << line.dump() << "\n";
        }
    }
    if (out) out->finish();
    for (auto& e : world.residency().errors()) std::fprintf(stderr, "not shown: %s\n", e.c_str());
    std::printf("peak resident share of the world on disk (%.1f MiB): %.2f%%\n", disk / 1048576.0, 100.0 * peak_share);
    return world.residency().stats().failures ? 1 : 0;
}

}  // namespace

command add_world_build(CLI::App& parent) {
    auto* app = parent.add_subcommand("world-build", "build an open world on disk chunk by chunk (chunked DAGs with LODs)");
    auto o = std::make_shared<build_options>();
    o->scene.add_to(app, false, max_world_mesh_resolution);
    app->add_option("--out", o->out, "the world's folder")->required();
    app->add_option("--chunk-bits", o->chunk_bits, "chunks of 2^N voxels a side")->check(CLI::Range(4, 10))->capture_default_str();
    app->add_option("--density", o->density, "children (of 8) a coarse voxel needs")->check(CLI::Range(1, 8))->capture_default_str();
    app->add_flag("--colours", o->colours, "colour-block attributes (LODs average colours) instead of exact palette indices");
    app->add_option("--appearance", o->appearance,
                    "a mesh world: also its appearance tables (compact records) of every chunk at every LOD, in "
                    "OUT/appearance/NAME");
    app->add_option("--colour-error", o->colour_error, "largest colour error in a block")->check(finite_range(0.0, 1.0))->capture_default_str();
    app->add_option("--tile", o->tile, "a .vox or built-in scene repeated X Y Z times")->expected(3)->check(CLI::Range(1, 4096));
    app->add_option("--threads", o->threads, "build threads (0: all)")->capture_default_str();
    app->add_option("--json", o->json_out, "append the build report as a JSON line");
    app->add_option("--chunk-times", o->chunk_times, "write each chunk job's LOD, cell, seconds and voxels (TSV)");
    app->add_flag("--force", o->force, "replace the world the folder holds, if it is another one");
    app->add_option("--shard", o->shard, "build share K of N (K from 0) of a world that N jobs build, then --finish");
    app->add_flag("--finish", o->finish, "finish a world built in shards (after every --shard K/N is done)");
    app->add_option("--mpi-schedule", o->mpi_schedule, "under mpirun: dynamic (units on demand) or static (balanced shares)")
        ->check(CLI::IsMember({"dynamic", "static"}))
        ->capture_default_str();
    return {app, [o] { return world_build(*o); }};
}

command add_world_fly(CLI::App& parent) {
    auto* app = parent.add_subcommand("world-fly", "stream a world along a camera path, trace each frame, report residency and cost");
    auto o = std::make_shared<fly_options>();
    app->add_option("dir", o->dir, "a world folder (voxray world-build)")->required()->check(CLI::ExistingDirectory);
    app->add_option("--backend", o->backend, "backend to trace on")->check(CLI::IsMember(backend_names()))->capture_default_str();
    app->add_option("--frames", o->frames, "frames along the path")->check(CLI::Range(1, 100000))->capture_default_str();
    app->add_option("--width", o->width)->check(CLI::Range(8, 8192))->capture_default_str();
    app->add_option("--height", o->height)->check(CLI::Range(8, 8192))->capture_default_str();
    app->add_option("--factor", o->factor, "StreamingFactor of LOD selection (Aokana Eq. 1)")->check(finite_range(0.01, 1000.0))->capture_default_str();
    app->add_option("--budget-mib", o->budget_mib, "most chunk bytes resident")->check(finite_range(1.0, 1e7))->capture_default_str();
    app->add_flag("--lod0", o->lod0, "every chunk at LOD 0, no budget: the reference frames");
    app->add_flag("--passes", o->passes, "render with the GPU-driven passes (chunk and tile selection, Hi-Z, visibility "
                  "buffer, colour resolve), timed pass by pass; primary visibility only, no shadow rays");
    app->add_flag("--raster", o->raster, "also mesh the shown chunks at their LOD and draw them with the Vulkan raster "
                  "path (POP inside chunks), with SSIM against the traced frame");
    app->add_option("--lod-bias", o->lod_bias, "--raster: POP t = log2(distance in a chunk's cells) - bias")
        ->check(finite_range(-64.0, 64.0))
        ->capture_default_str();
    app->add_option("--appearance", o->appearance,
                    "also walk each frame's LOD cut through the world's appearance tables of this set "
                    "(world-build MESH --appearance SET), on the CPU");
    app->add_option("--png-dir", o->png_dir,
                    "write frame_NNN.png here (with --raster: raster_and_traced_NNN.png too; with --appearance: "
                    "appearance_NNN.png)");
    app->add_option("--json", o->json_out, "append one JSON line a frame");
    return {app, [o] {
                int rc = 2;
                bool found = false;
                for_each_type(backends{}, [&]<class B>() {
                    if (!found && o->backend == B::name) found = true, rc = fly<B>(*o);
                });
                return rc;
            }};
}

}  // namespace voxray::tool
