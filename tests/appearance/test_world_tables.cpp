// Appearance tables for a world's chunks (appearance/world/chunk_tables.hpp) and pieces walked
// as one (appearance/world/placed_walker.hpp): one piece walks as its own walker, moved or
// not; a world's LOD 0 tables are the rows of the whole model's table; its LOD 0 cut walks as
// the whole model does, and its LOD 1 and 2 cuts as the whole model's chain re-sampled in
// memory; a missing or foreign table, a bad set name and a world of another mesh or resolution
// are errors naming them; a stopped build resumes.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>

#include "error_of.hpp"
#include "temp_dir.hpp"
#include "walk_tables.hpp"
#include "voxray/appearance/world/chunk_tables.hpp"
#include "voxray/appearance/resample.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/embree/triangle_scene.hpp"
#include "voxray/io/voxelizer.hpp"
#include "voxray/world/build/mesh_source.hpp"
#include "voxray/world/build/world_build.hpp"

namespace voxray {
namespace {

using namespace appearance;
using whole_walker = appearance_walker<kernels::dense_grid_kernel>;

// A rolling height field of 4 colours over 10 x 10 units, 3 units high: at resolution 72
// (16^3 chunks) it spans 5 x 2 x 5 chunks and reaches LOD 2.
io::triangle_mesh hills() {
    io::triangle_mesh m;
    constexpr int n = 12;
    auto height = [](int i, int j) { return 1.5 + 1.5 * std::sin(0.7 * i) * std::cos(0.5 * j); };
    for (int j = 0; j <= n; ++j)
        for (int i = 0; i <= n; ++i) m.positions.push_back({10.0 * i / n, height(i, j), 10.0 * j / n});
    const glm::vec4 colours[4] = {
        {0.8f, 0.2f, 0.1f, 1}, {0.1f, 0.7f, 0.2f, 1}, {0.2f, 0.3f, 0.9f, 1}, {0.9f, 0.9f, 0.2f, 1}};
    for (const glm::vec4& c : colours) {
        io::mesh_material mat;
        mat.base_colour = c;
        m.surface.materials.push_back(mat);
    }
    m.group_names = {"hills"};
    for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
            auto at = [&](int a, int b) { return std::uint32_t(b * (n + 1) + a); };
            m.triangles.push_back({at(i, j), at(i, j + 1), at(i + 1, j + 1)});
            m.triangles.push_back({at(i, j), at(i + 1, j + 1), at(i + 1, j)});
            std::uint32_t material = std::uint32_t((i / 3 + j / 3) % 4);
            m.surface.triangle_materials.insert(m.surface.triangle_materials.end(), {material, material});
        }
    return m;
}

constexpr int resolution = 72;
const sampling_options few_rays{.rays = 48, .stratified = true, .seed = 3};

// The world of `mesh` in `dir` (16^3 chunks, each LOD voxel where any child is) and its
// compact tables, set "compact".
struct hills_world {
    world_manifest manifest;
    chunk_tables_report tables;
};

hills_world build_hills_world(const io::triangle_mesh& mesh, const std::filesystem::path& dir) {
    world_build_options build;
    build.chunk_bits = 4, build.density = 1, build.threads = 2;
    build_world(mesh_source(mesh, resolution), dir, build);
    embree::triangle_scene scene(mesh, io::make_grid_map(mesh.bounds(), resolution));
    chunk_tables_options tables;
    tables.sampling = few_rays, tables.threads = 2;
    chunk_tables_report report = build_chunk_tables(scene, mesh, resolution, dir, tables);
    return {read_manifest(dir), report};
}

std::vector<chunk_key> chunks_at(const world_manifest& m, int lod) {
    std::vector<chunk_key> keys;
    for (const manifest_chunk& c : m.chunks)
        if (c.key.lod == lod) keys.push_back(c.key);
    return keys;
}

// Rays from a camera above the hills, looking down across them.
std::vector<ray> hills_rays(int size) {
    camera cam = look_at({-8.0f, 30.0f, -8.0f}, {20.0f, 4.0f, 20.0f}, 50.0f, {0.0f, 1.0f, 0.0f});
    return primary_rays(cam, size, size);
}

const appearance_light unlit{.to_light = {0.0f, 1.0f, 0.0f}, .ambient = 1.0f, .shadows = false};

TEST(appearance_placed_walk, one_piece_walks_as_its_own_walker_in_place_or_moved) {
    voxel_model model = io::voxelize(hills(), {.resolution = resolution, .threads = 2});
    dense_grid grid(model);
    auto own = std::make_shared<const whole_walker>(std::vector<std::uint32_t>(grid.blob().begin(), grid.blob().end()),
                                                    test::uniform_table(model, 9), 1);
    const glm::ivec3 box = model.bounds().max;
    const int edge = std::max({box.x, box.y, box.z});
    placed_walker<whole_walker> in_place, moved;
    in_place.add({glm::ivec3(0), 1, edge}, own);
    const glm::ivec3 shift(64, -32, 16);
    moved.add({shift, 1, edge}, own);
    std::vector<ray> rays = hills_rays(48);
    std::size_t hits = 0;
    for (const ray& r : rays) {
        appearance_pixel want = own->walk_one(r, unlit), got = in_place.walk_one(r, unlit);
        ray shifted = r;
        shifted.origin += glm::vec3(shift);
        appearance_pixel far = moved.walk_one(shifted, unlit);
        hits += want.is_hit();
        for (const appearance_pixel* p : {&got, &far}) {
            ASSERT_EQ(p->status, want.status);
            EXPECT_NEAR(p->r, want.r, 1e-5f);
            EXPECT_NEAR(p->g, want.g, 1e-5f);
            EXPECT_NEAR(p->b, want.b, 1e-5f);
            EXPECT_NEAR(p->transmittance, want.transmittance, 1e-5f);
            EXPECT_EQ(p->visits, want.visits);
        }
        EXPECT_EQ(glm::ivec3(got.x, got.y, got.z), glm::ivec3(want.x, want.y, want.z));
        if (want.is_hit()) {
            EXPECT_EQ(glm::ivec3(far.x, far.y, far.z), glm::ivec3(want.x, want.y, want.z) + shift);
            EXPECT_NEAR(got.t, want.t, 1e-4f);
        }
    }
    EXPECT_GT(hits, rays.size() / 4);
}

TEST(appearance_chunk_tables, lod0_tables_are_the_rows_of_the_whole_models_table) {
    io::triangle_mesh mesh = hills();
    test::temp_dir dir;
    auto [m, report] = build_hills_world(mesh, dir.path);
    ASSERT_EQ(m.grid.top_lod, 2);
    ASSERT_EQ(report.lods.size(), 3u);

    voxel_model model = io::voxelize(mesh, {.resolution = resolution, .threads = 2});
    embree::triangle_scene scene(mesh, io::make_grid_map(mesh.bounds(), resolution));
    appearance_table whole =
        precompute(scene, mesh, model, {.kind = record_kind::compact, .sampling = few_rays, .threads = 2});
    EXPECT_EQ(report.lods[0].voxels, whole.size());
    std::size_t rows = 0;
    for (const chunk_key& k : chunks_at(m, 0)) {
        appearance_table t = load_table(chunk_table_path(dir.path, "compact", k));
        const glm::ivec3 corner = chunk_placement(m.grid, k).origin;
        for (std::size_t row = 0; row < t.size(); ++row, ++rows) {
            auto w = whole.row_of(t.voxels[row] + corner);
            ASSERT_TRUE(w.has_value());
            auto mine = t.record(row), theirs = whole.record(*w);
            // The head's words past the face index; then the faces themselves.
            for (int k = 1; k < VX_APP_COMPACT_WORDS; ++k) ASSERT_EQ(mine[std::size_t(k)], theirs[std::size_t(k)]);
            std::uint32_t count = VX_APP_FACES(mine[1]);
            for (std::uint32_t f = 0; f < count * VX_APP_FACE_WORDS; ++f)
                ASSERT_EQ(t.faces[mine[0] * VX_APP_FACE_WORDS + f], whole.faces[theirs[0] * VX_APP_FACE_WORDS + f]);
        }
    }
    EXPECT_EQ(rows, whole.size());
}

// The chain of `model`'s tables kept in memory: LOD 0 from the triangles, each next level
// re-sampled from the one below over coarser_voxels (what the world's LODs are at density 1).
struct whole_chain {
    std::vector<voxel_model> models;
    std::vector<std::unique_ptr<whole_walker>> walkers;
};

whole_chain chain_of(const io::triangle_mesh& mesh, int levels) {
    whole_chain c;
    c.models.push_back(io::voxelize(mesh, {.resolution = resolution, .threads = 2}));
    embree::triangle_scene scene(mesh, io::make_grid_map(mesh.bounds(), resolution));
    const precompute_options o{.kind = record_kind::compact, .sampling = few_rays, .threads = 2};
    for (int lod = 0; lod < levels; ++lod) {
        if (lod > 0) c.models.push_back(coarser_voxels(c.models.back()));
        const voxel_model& model = c.models.back();
        appearance_table t = lod == 0 ? precompute(scene, mesh, model, o) : resample(*c.walkers.back(), model, o);
        dense_grid grid(model);
        c.walkers.push_back(std::make_unique<whole_walker>(
            std::vector<std::uint32_t>(grid.blob().begin(), grid.blob().end()), t, 2));
    }
    return c;
}

float largest_channel(glm::vec3 v) { return std::max({std::abs(v.x), std::abs(v.y), std::abs(v.z)}); }

TEST(appearance_chunk_tables, each_lods_cut_walks_as_the_whole_models_chain) {
    io::triangle_mesh mesh = hills();
    test::temp_dir dir;
    const world_manifest m = build_hills_world(mesh, dir.path).manifest;
    whole_chain chain = chain_of(mesh, m.grid.top_lod + 1);
    const std::vector<ray> rays = hills_rays(48);
    for (int lod = 0; lod <= m.grid.top_lod; ++lod) {
        SCOPED_TRACE("LOD " + std::to_string(lod));
        std::vector<appearance_pixel> got = cut_walker(dir.path, m, "compact", chunks_at(m, lod)).walk(rays, unlit, 2);
        std::vector<ray> coarse_rays = rays;  // the same rays in the level's voxels, 2^lod world voxels wide
        for (ray& r : coarse_rays) r.origin /= float(1 << lod);
        std::vector<appearance_pixel> want = chain.walkers[std::size_t(lod)]->walk(coarse_rays, unlit);
        float largest = 0, mean_difference = 0;
        glm::vec3 mean_got(0.0f), mean_want(0.0f);
        float covered_got = 0, covered_want = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            glm::vec3 a(got[i].r, got[i].g, got[i].b), b(want[i].r, want[i].g, want[i].b);
            largest = std::max(largest, largest_channel(a - b));
            mean_difference += largest_channel(a - b);
            mean_got += a, mean_want += b;
            covered_got += 1.0f - got[i].transmittance, covered_want += 1.0f - want[i].transmittance;
        }
        const float n = float(rays.size());
        EXPECT_GT(covered_want, 0.25f * n);
        if (lod == 0) {  // the same records and voxels, walked chunk by chunk
            EXPECT_EQ(largest, 0.0f);
            for (std::size_t i = 0; i < rays.size(); ++i) {
                if (want[i].is_hit()) {
                    EXPECT_EQ(glm::ivec3(got[i].x, got[i].y, got[i].z), glm::ivec3(want[i].x, want[i].y, want[i].z));
                }
            }
        } else {  // the same level re-sampled with other ray bits (the hashes): other noise, the same picture
            EXPECT_LT(largest_channel(mean_got - mean_want) / n, 0.003f);  // 0.0011 measured
            EXPECT_NEAR(covered_got / n, covered_want / n, 0.002f);           // 0.0003
            EXPECT_LT(mean_difference / n, 0.012f);                            // 0.0068
        }
    }
}

TEST(appearance_chunk_tables, foreign_or_missing_tables_bad_set_names_and_other_meshes_are_errors_naming_them) {
    io::triangle_mesh mesh = hills();
    test::temp_dir dir;
    const world_manifest m = build_hills_world(mesh, dir.path).manifest;
    std::vector<chunk_key> lod0 = chunks_at(m, 0);
    ASSERT_GE(lod0.size(), 2u);
    // Two chunks of other voxel counts: the one's table put in place of the other's.
    std::sort(lod0.begin(), lod0.end(), [&](const chunk_key& a, const chunk_key& b) {
        return m.find(a)->voxel_count < m.find(b)->voxel_count;
    });
    const chunk_key small = lod0.front(), big = lod0.back();
    ASSERT_NE(m.find(small)->voxel_count, m.find(big)->voxel_count);
    const auto big_table = chunk_table_path(dir.path, "compact", big);
    std::filesystem::copy_file(chunk_table_path(dir.path, "compact", small), big_table,
                               std::filesystem::copy_options::overwrite_existing);
    std::string e = test::error_of([&] { cut_walker(dir.path, m, "compact", std::vector<chunk_key>{big}); });
    EXPECT_NE(e.find(big_table.string()), std::string::npos) << e;
    EXPECT_NE(e.find("rows, but its chunk has " + std::to_string(m.find(big)->voxel_count)), std::string::npos) << e;

    std::filesystem::remove(big_table);
    e = test::error_of([&] { cut_walker(dir.path, m, "compact", std::vector<chunk_key>{big}); });
    EXPECT_NE(e.find(big_table.string() + ": missing"), std::string::npos) << e;
    e = test::error_of([&] { cut_walker(dir.path, m, "sggx", std::vector<chunk_key>{small}); });
    EXPECT_NE(e.find("set \"sggx\""), std::string::npos) << e;

    // A set is one folder inside the world's appearance folder.
    e = test::error_of([&] {
        embree::triangle_scene scene(mesh, io::make_grid_map(mesh.bounds(), resolution));
        chunk_tables_options outside;
        outside.set = "../outside";
        build_chunk_tables(scene, mesh, resolution, dir.path, outside);
    });
    EXPECT_NE(e.find("\"../outside\" must be one folder name"), std::string::npos) << e;

    // Tables of a world built from another mesh, or at another resolution.
    io::triangle_mesh moved = mesh;
    moved.positions[0].y += 0.5;
    for (auto [other, at] : {std::pair{&moved, resolution}, std::pair{&mesh, resolution + 8}}) {
        e = test::error_of([&] {
            embree::triangle_scene scene(*other, io::make_grid_map(other->bounds(), at));
            build_chunk_tables(scene, *other, at, dir.path, chunk_tables_options{});
        });
        EXPECT_NE(e.find("was not built from this mesh at resolution " + std::to_string(at)), std::string::npos) << e;
    }
}

// Every table file of `set`, path to bytes.
std::map<std::string, std::string> table_files(const std::filesystem::path& dir, const std::string& set) {
    std::map<std::string, std::string> out;
    for (const auto& f : std::filesystem::recursive_directory_iterator(dir / "appearance" / set))
        if (f.path().extension() == ".vxap") {
            std::ifstream in(f.path(), std::ios::binary);
            out[f.path().string()] = std::string(std::istreambuf_iterator<char>(in), {});
        }
    return out;
}

// A build run again keeps every table; one that lost a LOD 0 table (or holds a damaged one)
// makes it and its ancestors again, the same bytes; other options start the set afresh.
TEST(appearance_chunk_tables, a_stopped_build_resumes_and_other_options_start_afresh) {
    io::triangle_mesh mesh = hills();
    test::temp_dir dir;
    hills_world first = build_hills_world(mesh, dir.path);
    const world_manifest& m = first.manifest;
    EXPECT_EQ(first.tables.resumed, 0u);
    const auto made = table_files(dir.path, "compact");
    ASSERT_EQ(made.size(), m.chunks.size());
    embree::triangle_scene scene(mesh, io::make_grid_map(mesh.bounds(), resolution));
    chunk_tables_options again;
    again.sampling = few_rays, again.threads = 1;  // the thread count is not an option that changes a table
    chunk_tables_report r = build_chunk_tables(scene, mesh, resolution, dir.path, again);
    EXPECT_EQ(r.resumed, m.chunks.size());
    EXPECT_EQ(r.lods[0].voxels, 0u);  // nothing sampled

    // One LOD 0 table gone, another cut short: those two and their ancestors (one a LOD
    // above each, shared from some LOD on) are made again, the rest kept.
    std::vector<chunk_key> lod0 = chunks_at(m, 0);
    const chunk_key gone = lod0.front(), damaged = lod0.back();
    std::filesystem::remove(chunk_table_path(dir.path, "compact", gone));
    std::filesystem::resize_file(chunk_table_path(dir.path, "compact", damaged), 100);
    std::set<chunk_key, chunk_key_less> remade;
    for (chunk_key k : {gone, damaged})
        for (; k.lod <= m.grid.top_lod; k = {k.lod + 1, k.cell >> 1})
            if (m.find(k)) remade.insert(k);
    r = build_chunk_tables(scene, mesh, resolution, dir.path, again);
    EXPECT_EQ(r.resumed, m.chunks.size() - remade.size());
    EXPECT_EQ(table_files(dir.path, "compact"), made);  // the same bytes as the first build's

    // Another seed: nothing kept, every table made again.
    chunk_tables_options other = again;
    other.sampling.seed = 9;
    r = build_chunk_tables(scene, mesh, resolution, dir.path, other);
    EXPECT_EQ(r.resumed, 0u);
    EXPECT_NE(table_files(dir.path, "compact"), made);
}

}  // namespace
}  // namespace voxray
