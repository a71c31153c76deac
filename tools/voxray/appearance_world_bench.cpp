// voxray appearance-world-bench: filtered appearance in a world's LOD chunks (issue 25, item 6).
// From a coloured mesh: a world on disk (world-build's chunks, every LOD voxel where any of
// its 8 children is), then appearance tables chunk by chunk (appearance/world/chunk_tables.hpp)
// in two chains that share LOD 0 (ours, compact records made from the triangles):
//   ours      LOD n: compact records re-sampled from LOD n - 1 through the walk
//   averages  LOD n: averages records (one colour, normal and opacity a voxel: the average-
//             colour LOD chunks) re-sampled the same way
// Then for each view the LOD cut at --factor (the StreamingFactor of world/lod_select.hpp)
// walked with each chain, against the frame of every chunk at LOD 0 (ours), 4 rays a pixel:
// MSE, PSNR and SSIM (appearance_pictures.hpp). One JSON line per view and chain after a header.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <set>
#include <tuple>
#include <memory>

#include <nlohmann/json.hpp>

#include "bench_header.hpp"
#include "cli.hpp"
#include "output.hpp"
#include "timing.hpp"
#include "voxray/rays/camera.hpp"

#if VOXRAY_WITH_EMBREE
#include "appearance_pictures.hpp"
#include "voxray/appearance/world/chunk_tables.hpp"
#include "voxray/embree/triangle_scene.hpp"
#include "voxray/gltf/coloured_mesh.hpp"
#include "voxray/world/build/mesh_source.hpp"
#include "voxray/world/build/world_build.hpp"
#include "voxray/world/lod_select.hpp"
#endif

namespace voxray::tool {

namespace {

struct world_bench_options {
    std::string mesh;
    int resolution = 256;
    int chunk_bits = 5;
    double factor = 2.0;
    int views = 3;
    int size = 256;
    float distance = 1.0f;  // the orbit cameras' distance, times auto_camera's
    unsigned threads = 2;
    std::string dir, json, images;
};

#if VOXRAY_WITH_EMBREE

namespace fs = std::filesystem;

// A scratch folder for the world unless --dir names one: removed when the bench ends.
class world_folder {
public:
    explicit world_folder(const std::string& dir) {
        if (!dir.empty()) {
            path_ = dir;
            return;
        }
        path_ = fs::temp_directory_path() / ("voxray-appearance-world-" + std::to_string(::getpid()));
        scratch_ = true;
    }
    ~world_folder() {
        std::error_code ec;
        if (scratch_) fs::remove_all(path_, ec);
    }
    world_folder(const world_folder&) = delete;
    world_folder& operator=(const world_folder&) = delete;
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
    bool scratch_ = false;
};

struct chain {
    std::string set;
    double seconds = 0;           // making its LOD >= 1 tables
    std::uint64_t coarse_voxels = 0;
};

// The LOD of the cut's chunk that holds world voxel v (-1 where none does).
int lod_at(const world_grid& g, const std::set<std::tuple<int, int, int, int>>& cut, glm::ivec3 v) {
    for (int lod = 0; lod <= g.top_lod; ++lod) {
        glm::ivec3 cell = (v - g.origin) >> (g.chunk_bits + lod);
        if (cut.count({lod, cell.x, cell.y, cell.z})) return lod;
    }
    return -1;
}

int appearance_world_bench(const world_bench_options& o) {
    std::unique_ptr<output_file> out;
    if (!o.json.empty()) {
        out = std::make_unique<output_file>(o.json, "--json");
        nlohmann::json header = results_header(own_command_line(), 1);
        header["format"] = "voxray-appearance-world-bench-1";
        out->stream() << header.dump() << "\n";
    }
    if (!o.images.empty()) fs::create_directories(o.images);
    io::triangle_mesh mesh = gltf::load_coloured_mesh(o.mesh);
    fs::path mesh_path(o.mesh);
    const std::string folder = mesh_path.parent_path().filename().string();
    const std::string scene_name = folder + "/" + mesh_path.filename().string();
    world_folder world(o.dir);
    const fs::path& dir = world.path();

    auto start = std::chrono::steady_clock::now();
    world_build_options build;
    build.chunk_bits = o.chunk_bits, build.density = 1, build.threads = o.threads;
    build.replace = o.dir.empty();  // a --dir that holds another world is refused, not replaced
    build_world(mesh_source(mesh, o.resolution), dir, build);
    const world_manifest m = read_manifest(dir);
    std::fprintf(stderr, "%s at %d: world of %zu chunks, LOD 0..%d, built in %.1f s\n", scene_name.c_str(),
                 o.resolution, m.chunks.size(), m.grid.top_lod, seconds_since(start));
    embree::triangle_scene scene(mesh, io::make_grid_map(mesh.bounds(), o.resolution));
    using appearance::record_kind;
    appearance::chunk_tables_options tables;
    tables.set = "ours", tables.threads = o.threads;
    appearance::chunk_tables_report ours_report =
        appearance::build_chunk_tables(scene, mesh, o.resolution, dir, tables);
    tables.set = "averages", tables.coarser = record_kind::averages, tables.finest_from = "ours";
    appearance::chunk_tables_report averages_report =
        appearance::build_chunk_tables(scene, mesh, o.resolution, dir, tables);
    auto coarse = [](const appearance::chunk_tables_report& r) {
        double s = 0;
        std::uint64_t v = 0;
        for (std::size_t lod = 1; lod < r.lods.size(); ++lod) s += r.lods[lod].seconds, v += r.lods[lod].voxels;
        return std::pair(s, v);
    };
    std::vector<chain> chains{{"ours", coarse(ours_report).first, coarse(ours_report).second},
                              {"averages", coarse(averages_report).first, coarse(averages_report).second}};
    std::fprintf(stderr,
                 "tables: LOD 0 %.1f s (%llu voxels), ours LOD 1+ %.1f s, averages LOD 1+ %.1f s (%llu voxels)\n",
                 ours_report.lods[0].seconds, (unsigned long long)ours_report.lods[0].voxels, chains[0].seconds,
                 chains[1].seconds, (unsigned long long)chains[0].coarse_voxels);

    const lod_tree tree(m);
    std::printf("%-24s %4s %4s %6s %-9s %9s %9s %7s %7s %8s %7s\n", "scene", "res", "view", "factor", "chain", "mse",
                "mse fg", "psnr", "ssim", "lod px %", "walk s");
    for (int view = 0; view < o.views; ++view) {
        camera cam = auto_camera(m.bounds, 1, view * 8 / o.views);
        cam.position = cam.target + (cam.position - cam.target) * o.distance;
        const shading light{light_direction(cam, true), 0.2f, glm::vec3(0.2f), false};
        const appearance_light walk_light{.to_light = light.to_light, .ambient = light.ambient, .shadows = false};
        const std::vector<ray> rays = four_rays_a_pixel(cam, o.size, o.size);
        auto keys_of = [](const std::vector<lod_choice>& choices) {
            std::vector<chunk_key> keys;
            for (const lod_choice& c : choices) keys.push_back(c.key);
            return keys;
        };
        const std::vector<chunk_key> lod0 = keys_of(tree.select(glm::dvec3(cam.position), 1e9));
        const std::vector<chunk_key> cut = keys_of(tree.select(glm::dvec3(cam.position), o.factor));
        std::set<std::tuple<int, int, int, int>> in_cut;
        std::vector<int> cut_chunks(std::size_t(m.grid.top_lod) + 1, 0);
        for (const chunk_key& k : cut) {
            in_cut.insert({k.lod, k.cell.x, k.cell.y, k.cell.z});
            ++cut_chunks[std::size_t(k.lod)];
        }

        std::vector<appearance_pixel> ref_px =
            appearance::cut_walker(dir, m, "ours", lod0).walk(rays, walk_light, o.threads);
        linear_picture ref = blend_four(ref_px, o.size, o.size, light.background);
        ref.coverage.assign(ref.rgb.size(), 0.0f);
        for (std::size_t i = 0; i < ref_px.size(); ++i) ref.coverage[i / 4] += 0.25f * (1.0f - ref_px[i].transmittance);
        const std::vector<std::uint8_t> ref8 = srgb8(ref);
        std::vector<std::vector<std::uint8_t>> strip{ref8};
        for (const chain& ch : chains) {
            const auto walker = appearance::cut_walker(dir, m, ch.set, cut);  // the chunks, read
            auto walk_start = std::chrono::steady_clock::now();
            std::vector<appearance_pixel> px = walker.walk(rays, walk_light, o.threads);
            double walk_seconds = seconds_since(walk_start);
            std::size_t hits = 0, coarse_hits = 0;
            for (const appearance_pixel& p : px)
                if (p.is_hit()) ++hits, coarse_hits += lod_at(m.grid, in_cut, {p.x, p.y, p.z}) > 0;
            const double lod_share = hits ? double(coarse_hits) / double(hits) : 0.0;
            std::vector<std::uint8_t> got8 = srgb8(blend_four(px, o.size, o.size, light.background));
            picture_errors e = compare(ref8, got8, ref.coverage, o.size, o.size);
            std::printf("%-24s %4d %4d %6.2f %-9s %9.5f %9.5f %7.2f %7.4f %8.1f %7.2f\n", scene_name.c_str(),
                        o.resolution, view, o.factor, ch.set.c_str(), e.mse, e.mse_foreground, e.psnr, e.ssim,
                        100.0 * lod_share, walk_seconds);
            std::fflush(stdout);
            if (out)
                out->stream() << nlohmann::json{{"scene", scene_name}, {"resolution", o.resolution},
                                                {"chunk_bits", o.chunk_bits}, {"factor", o.factor}, {"size", o.size},
                                                {"distance", o.distance}, {"view", view}, {"method", ch.set},
                                                {"mse", e.mse}, {"mse_foreground", e.mse_foreground},
                                                {"psnr", e.psnr}, {"ssim", e.ssim},
                                                {"coarse_hit_share", lod_share}, {"cut_chunks", cut_chunks},
                                                {"lod0_chunks", lod0.size()}, {"walk_seconds", walk_seconds},
                                                {"walk_threads", o.threads}, {"rays_per_pixel", 4},
                                                {"lod0_voxels", ours_report.lods[0].voxels},
                                                {"lod0_table_seconds", ours_report.lods[0].seconds},
                                                {"coarse_voxels", ch.coarse_voxels},
                                                {"coarse_table_seconds", ch.seconds}}
                                         .dump()
                              << "\n";
            strip.push_back(std::move(got8));
        }
        if (!o.images.empty())
            write_strip(strip, o.size, o.size,
                        (fs::path(o.images) / (folder + "_world_" + std::to_string(o.resolution) + "_view" +
                                               std::to_string(view) + ".png"))
                            .string());
    }
    if (out) out->finish();
    return 0;
}

#else

int appearance_world_bench(const world_bench_options&) {
    fail("appearance-world-bench needs Embree (LOD 0's tables are made from the triangles): this build has none");
}

#endif

}  // namespace

command add_appearance_world_bench(CLI::App& parent) {
    auto* app = parent.add_subcommand(
        "appearance-world-bench",
        "filtered appearance in a world's LOD chunks against average-colour ones, both against all-LOD-0 frames");
    auto o = std::make_shared<world_bench_options>();
    app->add_option("mesh", o->mesh, "a coloured mesh (.gltf, .glb, .obj, .ply)")->required()->check(CLI::ExistingFile);
    app->add_option("--resolution", o->resolution, "LOD 0 voxels along the mesh's longest axis")
        ->check(CLI::Range(16, 4096))->capture_default_str();
    app->add_option("--chunk-bits", o->chunk_bits, "chunks of 2^N voxels a side")
        ->check(CLI::Range(4, 10))
        ->capture_default_str();
    app->add_option("--factor", o->factor, "StreamingFactor of LOD selection (Aokana Eq. 1)")
        ->check(finite_range(0.01, 1000.0))->capture_default_str();
    app->add_option("--views", o->views, "views around the mesh")->check(CLI::Range(1, 8))->capture_default_str();
    app->add_option("--size", o->size, "picture side in pixels")->check(CLI::Range(16, 4096))->capture_default_str();
    app->add_option("--distance", o->distance, "the cameras' distance from the centre, times the default orbit's")
        ->check(finite_range(0.05, 100.0))->capture_default_str();
    app->add_option("--threads", o->threads, "threads of the tables and the walks")
        ->check(CLI::Range(1u, 256u))->capture_default_str();
    app->add_option("--dir", o->dir, "the world's folder, kept; one that holds another world is refused "
                                     "(default: a scratch folder, removed at the end)");
    app->add_option("--json", o->json, "write one JSON line per view and chain after a header line");
    app->add_option("--images", o->images, "write each view's strip (all LOD 0 | ours | averages) here as PNG");
    return {app, [o] { return appearance_world_bench(*o); }};
}

}  // namespace voxray::tool
