// voxray mesh-bench: the chunk mesher's figures per scene, one JSON line per scene after a
// header line. Timings on one thread: every (chunk, run) pair is a sample, so a one-chunk
// scene gives the spread over runs and a large scene the spread over its chunks. POP's cost
// is the difference of the medians with POP order on and off, per quad. The occupancy mask
// (bytes -> bits) and the reading of chunks from the model are timed apart, as the anchors
// leave them out. Throughput runs whole chunks on 1 and on --threads threads. The peer,
// meshoptimizer simplifying to each level's triangle count, runs on up to 8 chunks. Then
// remeshing after --edits random edits on the brickmap and NAADF (mesh_remesh.hpp), and the
// mesher kernel on every backend (meshing/kernel.h) on up to 8 chunks, against the CPU's words.
#include <algorithm>
#include <chrono>
#include <cstdio>

#include <nlohmann/json.hpp>

#include "bench_header.hpp"
#include "cli.hpp"
#include "mesh_peer.hpp"
#include "mesh_remesh.hpp"
#include "mesh_scene.hpp"
#include "output.hpp"
#include "scene.hpp"
#include "timing.hpp"
#include "voxray/meshing/kernel_meshers.hpp"
#include "voxray/meshing/occupancy.hpp"

namespace voxray::tool {

namespace {

struct mesh_bench_options {
    scene_options scene;
    unsigned threads = 2;
    double seconds = 0.4;  // timing budget per scene and configuration
    std::size_t max_chunks = 256;
    int edits = 20;  // rounds of remeshing after one random edit, on the brickmap and NAADF
    int kernel_runs = 3;  // timed runs of the mesher kernel on each backend (after one untimed)
    std::string json;
};

// Up to `most` chunks of the scene, evenly spread; the empty chunk at the origin when the
// scene has no voxel (the empty-chunk case).
std::vector<meshing::chunk_voxels> read_chunks(const voxel_model& model, std::size_t most, std::vector<double>& read_us) {
    auto origins = meshing::chunk_origins(model);
    if (origins.empty()) origins.push_back({0, 0, 0});
    std::vector<glm::ivec3> picked;
    for (std::size_t i = 0; i < std::min(most, origins.size()); ++i) picked.push_back(origins[i * origins.size() / std::min(most, origins.size())]);
    std::vector<meshing::chunk_voxels> chunks(picked.size());
    std::vector<std::uint8_t> scratch;
    for (std::size_t i = 0; i < picked.size(); ++i) {
        auto start = std::chrono::steady_clock::now();
        meshing::fill_chunk(model, picked[i], chunks[i], scratch);
        read_us.push_back(seconds_since(start) * 1e6);
    }
    return chunks;
}

// One-thread samples (µs per chunk) of meshing every chunk `runs` times with `options`.
std::vector<double> time_meshing(const std::vector<meshing::chunk_voxels>& chunks, meshing::mesher_options options, int runs) {
    meshing::mesher mesher(options);
    meshing::chunk_mesh out;
    std::vector<double> samples;
    for (int run = 0; run < runs; ++run)
        for (auto& c : chunks) {
            auto start = std::chrono::steady_clock::now();
            mesher.mesh(c, out);
            samples.push_back(seconds_since(start) * 1e6);
        }
    return samples;
}

// Chunks meshed per second on `threads` threads, for about `budget` seconds of work.
double chunks_per_second(const std::vector<meshing::chunk_voxels>& chunks, unsigned threads, double chunk_seconds, double budget) {
    std::size_t items = std::max<std::size_t>(std::size_t(budget * threads / std::max(chunk_seconds, 1e-7)), threads * 4);
    std::vector<meshing::mesher> meshers(threads);
    std::vector<meshing::chunk_mesh> outs(threads);
    auto start = std::chrono::steady_clock::now();
    parallel_for(items, threads, [&](std::size_t i, unsigned w) { meshers[w].mesh(chunks[i % chunks.size()], outs[w]); });
    return double(items) / seconds_since(start);
}

double occupancy_us(const meshing::chunk_voxels& c) {
    std::vector<std::uint64_t> rows(meshing::chunk_edge * meshing::chunk_edge);
    std::vector<double> samples;
    for (int run = 0; run < 300; ++run) {
        auto start = std::chrono::steady_clock::now();
        meshing::occupancy_rows(c.material.data(), int(rows.size()), rows.data());
        samples.push_back(seconds_since(start) * 1e6);
    }
    return percentile(samples, 0.5);
}

// The mesher kernel on every backend over `chunks` at once (AO off, POP on), meshes read
// back: wall ms of the median run, per chunk, and whether the words equal the CPU's `cpu`.
nlohmann::json kernel_figures(const std::vector<meshing::chunk_voxels>& chunks,
                              const std::vector<meshing::chunk_mesh>& cpu, int runs) {
    nlohmann::json rows = nlohmann::json::array();
    for_each_type(meshing::kernel_meshers{}, [&]<class Mesher>() {
        Mesher kernel;
        std::vector<meshing::chunk_mesh> got = kernel.mesh(chunks);  // untimed: builds the program
        bool equal = true;
        for (std::size_t i = 0; i < chunks.size(); ++i)
            equal = equal && got[i].words == cpu[i].words && got[i].table == cpu[i].table;
        std::vector<double> ms;
        for (int run = 0; run < runs; ++run) {
            auto start = std::chrono::steady_clock::now();
            kernel.mesh(chunks);
            ms.push_back(seconds_since(start) * 1e3);
        }
        double median = percentile(ms, 0.5);
        rows.push_back({{"backend", Mesher::backend_name()},
                        {"device", kernel.device_name()},
                        {"chunks", chunks.size()},
                        {"runs", runs},
                        {"ms_median", median},
                        {"us_per_chunk", median * 1e3 / double(chunks.size())},
                        {"equal_to_cpu", equal}});
    });
    return rows;
}

nlohmann::json bench_scene(const std::string& spec, const mesh_bench_options& o) {
    voxel_model model = load_scene(spec, o.scene);
    std::vector<double> read_us;
    auto chunks = read_chunks(model, o.max_chunks, read_us);

    // Runs: enough for the budget, at least 3; AO's runs capped (it is the slow option).
    auto probe = time_meshing(chunks, {}, 1);
    double pass_seconds = 0;
    for (double us : probe) pass_seconds += us * 1e-6;
    int runs = int(std::clamp(o.seconds / std::max(pass_seconds, 1e-9), 3.0, 500.0));
    std::fprintf(stderr, "meshing %zu chunk(s) x %d runs ...\n", chunks.size(), runs);
    auto pop = time_meshing(chunks, {}, runs);
    auto plain = time_meshing(chunks, {.pop_order = false}, runs);
    auto ao = time_meshing(chunks, {.ambient_occlusion = true}, std::min(runs, 20));

    // The meshes themselves, and the squashed-face pass on them.
    meshing::mesher mesher;
    std::vector<meshing::chunk_mesh> before(chunks.size()), after;
    std::vector<double> squashed_us;
    std::uint64_t moved = 0, faces = 0, quads = 0, bytes = 0;
    for (std::size_t i = 0; i < chunks.size(); ++i) {
        mesher.mesh(chunks[i], before[i]);
        faces += covered_faces(before[i]);
        quads += before[i].quad_count();
        bytes += before[i].bytes();
    }
    after = before;
    for (auto& m : after) {
        auto start = std::chrono::steady_clock::now();
        moved += meshing::remove_squashed_faces(m).moved;
        squashed_us.push_back(seconds_since(start) * 1e6);
    }
    nlohmann::json quads_before = nlohmann::json::array(), quads_after = nlohmann::json::array();
    nlohmann::json overdraw_before = nlohmann::json::array(), overdraw_after = nlohmann::json::array();
    double overdraw_max = 1, overdraw_max_before = 1;
    for (int level = 0; level < VX_MESH_LEVELS; ++level) {
        auto b = figures_at(before, level), a = figures_at(after, level);
        quads_before.push_back(b.quads), quads_after.push_back(a.quads);
        overdraw_before.push_back(b.overdraw.ratio()), overdraw_after.push_back(a.overdraw.ratio());
        overdraw_max = std::max(overdraw_max, a.overdraw.ratio());
        overdraw_max_before = std::max(overdraw_max_before, b.overdraw.ratio());
    }

    // The peer on up to 8 of the chunks: meshoptimizer at each POP level's triangle count.
    std::vector<meshing::chunk_mesh> peer_input(before.begin(), before.begin() + std::ptrdiff_t(std::min<std::size_t>(8, before.size())));
    std::fprintf(stderr, "meshoptimizer on %zu chunk(s) ...\n", peer_input.size());
    nlohmann::json peer = meshoptimizer_levels(peer_input, model.up_axis);

    std::fprintf(stderr, "remeshing after %d edits on the brickmap and NAADF ...\n", o.edits);
    nlohmann::json remesh = remesh_figures(model, o.edits);

    std::size_t kernel_chunks = std::min<std::size_t>(8, chunks.size());
    std::fprintf(stderr, "the mesher kernel on every backend, %zu chunk(s) ...\n", kernel_chunks);
    auto kernel_end = std::ptrdiff_t(kernel_chunks);
    nlohmann::json kernel = kernel_figures({chunks.begin(), chunks.begin() + kernel_end},
                                           {before.begin(), before.begin() + kernel_end}, o.kernel_runs);

    double median = percentile(pop, 0.5), n = double(chunks.size());
    double one = chunks_per_second(chunks, 1, median * 1e-6, o.seconds);
    double many = chunks_per_second(chunks, o.threads, median * 1e-6, o.seconds);
    double pop_ns = quads ? (median - percentile(plain, 0.5)) * 1e3 * n / double(quads) : 0;
    return {{"type", "mesh"},
            {"scene", scene_label(spec)},
            {"chunks", chunks.size()},
            {"runs", runs},
            {"us_min", percentile(pop, 0)},
            {"us_median", median},
            {"us_p95", percentile(pop, 0.95)},
            {"us_median_no_pop", percentile(plain, 0.5)},
            {"us_median_ao", percentile(ao, 0.5)},
            {"mask_us", occupancy_us(chunks[0])},
            {"mask_path", meshing::occupancy_path_name()},
            {"read_us_median", percentile(read_us, 0.5)},
            {"faces", faces},
            {"quads", quads},
            {"faces_per_quad", quads ? double(faces) / double(quads) : 0},
            {"ns_per_face", faces ? median * 1e3 * n / double(faces) : 0},
            {"bytes_per_quad", VX_MESH_QUAD_WORDS * 4},
            {"table_bytes", VX_MESH_TABLE_ENTRIES * 4},
            {"bytes_per_chunk", double(bytes) / n},
            {"pop_ns_per_quad", pop_ns},
            {"squashed_us_median", percentile(squashed_us, 0.5)},
            {"squashed_moved", moved},
            {"quads_per_level", quads_before},
            {"quads_per_level_after_squashed", quads_after},
            {"overdraw_per_level", overdraw_before},
            {"overdraw_per_level_after_squashed", overdraw_after},
            {"overdraw_max_before_squashed", overdraw_max_before},
            {"overdraw_max", overdraw_max},
            {"threads", o.threads},
            {"chunks_per_s_1", one},
            {"chunks_per_s", many},
            {"thread_scaling", many / one},
            {"meshoptimizer_chunks", peer_input.size()},
            {"meshoptimizer", peer},
            {"remesh", remesh},
            {"kernel", kernel}};
}

int mesh_bench(const mesh_bench_options& o) {
    std::unique_ptr<output_file> out;
    if (!o.json.empty()) {
        out = std::make_unique<output_file>(o.json, "--json");
        nlohmann::json header = results_header(own_command_line(), 1);
        header["format"] = "voxray-mesh-bench-1";
        out->stream() << header.dump() << "\n";
    }
    std::printf("%-22s %6s %9s %9s %9s %9s %8s %8s %7s %8s %9s\n", "scene", "chunks", "us min", "us med", "us p95", "quads",
                "face/q", "pop ns/q", "ns/face", "overdraw", "chunks/s");
    for (auto& spec : o.scene.scenes) {
        auto row = bench_scene(spec, o);
        std::printf("%-22s %6zu %9.1f %9.1f %9.1f %9llu %8.2f %8.2f %7.2f %8.3f %9.0f\n", row["scene"].get<std::string>().c_str(),
                    row["chunks"].get<std::size_t>(), row["us_min"].get<double>(), row["us_median"].get<double>(),
                    row["us_p95"].get<double>(), (unsigned long long)row["quads"].get<std::uint64_t>(),
                    row["faces_per_quad"].get<double>(), row["pop_ns_per_quad"].get<double>(), row["ns_per_face"].get<double>(),
                    row["overdraw_max"].get<double>(), row["chunks_per_s"].get<double>());
        std::fflush(stdout);
        if (out) out->stream() << row.dump() << "\n";
    }
    if (out) out->finish();
    return 0;
}

}  // namespace

command add_mesh_bench(CLI::App& parent) {
    auto* app = parent.add_subcommand("mesh-bench", "time the chunk mesher (POP order, AO, squashed faces) on scenes");
    auto o = std::make_shared<mesh_bench_options>();
    o->scene.add_to(app, true);
    app->add_option("--threads", o->threads, "threads of the throughput run")->check(CLI::Range(1u, 256u))->capture_default_str();
    app->add_option("--seconds", o->seconds, "timing budget per scene and configuration")
        ->check(finite_range(0.01, 600))->capture_default_str();
    app->add_option("--max-chunks", o->max_chunks, "most chunks of a scene timed (evenly spread)")
        ->check(CLI::Range(std::size_t(1), std::size_t(1) << 20))->capture_default_str();
    app->add_option("--edits", o->edits, "rounds of one random edit, then remeshing, on the brickmap and NAADF")
        ->check(CLI::Range(0, 100000))->capture_default_str();
    app->add_option("--kernel-runs", o->kernel_runs, "timed runs of the mesher kernel on each backend")
        ->check(CLI::Range(1, 1000))->capture_default_str();
    app->add_option("--json", o->json, "write one JSON line per scene after a header line");
    return {app, [o] { return mesh_bench(*o); }};
}

}  // namespace voxray::tool
