// The compositing walk on every backend (issue 25's determinism target): the CPU's scalar
// lanes, its SIMD lanes (8 and 16 wide where the CPU has them), OpenCL and Vulkan give the
// same pixels bit for bit, for every registered structure and every record kind, on tables
// precomputed from a coloured mesh; opaque records stop at the first-hit kernel's voxel on
// every backend.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "test_data.hpp"
#include "voxray/appearance/precompute.hpp"
#include "voxray/appearance/shadows.hpp"
#include "voxray/cpu.hpp"
#include "voxray/cpu/appearance_samples.hpp"
#include "voxray/cpu/appearance_walk.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/embree/triangle_scene.hpp"
#include "voxray/generated/structures.hpp"
#include "voxray/gltf/coloured_mesh.hpp"
#include "voxray/io/voxelizer.hpp"
#include "voxray/opencl/appearance_walk.hpp"
#include "voxray/tracer.hpp"
#include "voxray/vulkan/appearance_walk.hpp"
#include "walk_tables.hpp"

namespace voxray {
namespace {

using appearance::appearance_table;
using appearance::record_kind;

// The first pixel whose bytes differ, described; empty when all agree.
std::string first_difference(const std::vector<appearance_pixel>& want, const std::vector<appearance_pixel>& got) {
    if (want.size() != got.size()) return "sizes " + std::to_string(want.size()) + " and " + std::to_string(got.size());
    for (std::size_t i = 0; i < want.size(); ++i) {
        if (std::memcmp(&want[i], &got[i], sizeof(appearance_pixel)) == 0) continue;
        const appearance_pixel &a = want[i], &b = got[i];
        char text[400];
        std::snprintf(text, sizeof text,
                      "pixel %zu: rgb (%.9g %.9g %.9g) T %.9g t %.9g voxel (%d %d %d) visits %u steps %u status %u "
                      "against rgb (%.9g %.9g %.9g) T %.9g t %.9g voxel (%d %d %d) visits %u steps %u status %u",
                      i, a.r, a.g, a.b, a.transmittance, a.t, a.x, a.y, a.z, a.visits, a.steps, a.status, b.r, b.g,
                      b.b, b.transmittance, b.t, b.x, b.y, b.z, b.visits, b.steps, b.status);
        return text;
    }
    return "";
}

// The SIMD widths this CPU runs (the CI machine has both).
std::vector<unsigned> simd_widths() {
    std::vector<unsigned> widths;
    if (kernels::cpu_has_avx2()) widths.push_back(8);
    if (kernels::cpu_has_avx512()) widths.push_back(16);
    return widths;
}

const appearance_light kitchen_light{.to_light = glm::normalize(glm::vec3(0.3f, 1.0f, 0.5f)), .ambient = 0.2f};

struct walk_scene {
    voxel_model model;
    std::vector<std::pair<std::string, appearance_table>> tables;  // every record kind, and opaque records
    std::vector<ray> rays;
};

// The kitchen at 32^3: furniture, walls and thin parts, so walks blend several voxels.
const walk_scene& kitchen() {
    static const walk_scene scene = [] {
        walk_scene s;
        io::triangle_mesh mesh = gltf::load_coloured_mesh(*test::data_dir() / "mesh" / "kitchen" / "scene.gltf");
        const int resolution = 32;
        s.model = io::voxelize(mesh, {.resolution = resolution, .threads = 2});
        embree::triangle_scene triangles(mesh, io::make_grid_map(mesh.bounds(), resolution));
        for (auto [name, kind] : {std::pair{"averages", record_kind::averages}, {"compact", record_kind::compact},
                                  {"six", record_kind::six}, {"sggx", record_kind::sggx},
                                  {"faithful", record_kind::faithful}})
            s.tables.emplace_back(name, appearance::precompute(triangles, mesh, s.model, {.kind = kind, .threads = 2}));
        s.tables.emplace_back("opaque", test::uniform_table(s.model, 15));
        appearance_table shadowed = s.tables[1].second;  // compact, with shadows of the test's light
        dense_grid grid(s.model);
        appearance_walker<kernels::dense_grid_kernel> walker({grid.blob().begin(), grid.blob().end()}, shadowed, 2);
        appearance::precompute_shadows(walker, shadowed, kitchen_light.to_light);
        s.tables.emplace_back("shadowed compact", std::move(shadowed));
        s.rays = test::camera_rays(s.model, 40);
        return s;
    }();
    return scene;
}

TEST(appearance_walk_backends, every_backend_gives_the_same_pixels_bit_for_bit) {
    VOXRAY_REQUIRE_DATA();
    const walk_scene& s = kitchen();
    const appearance_light& light = kitchen_light;
    for_each_type(registered::structures{}, [&]<class S>() {
        using kernel = typename S::kernel;
        S structure(s.model);
        std::span<const std::uint32_t> blob = structure.blob();
        for (const auto& [name, table] : s.tables) {
            SCOPED_TRACE(std::string(kernel::name) + ", " + name + " records");
            std::vector<appearance_pixel> cpu =
                appearance_walker<kernel, cpu_scalar>({blob.begin(), blob.end()}, table, 2).walk(s.rays, light);
            for (unsigned width : simd_widths()) {
                appearance_walker<kernel> simd({blob.begin(), blob.end()}, table, {.threads = 2, .simd_width = width});
                ASSERT_EQ(simd.simd_width(), width);
                EXPECT_EQ(first_difference(cpu, simd.walk(s.rays, light)), "") << width << " SIMD lanes against scalar";
            }
            std::vector<appearance_pixel> opencl = opencl_appearance_walker<kernel>(blob, table).walk(s.rays, light);
            std::vector<appearance_pixel> vulkan = vulkan_appearance_walker<kernel>(blob, table).walk(s.rays, light);
            EXPECT_EQ(first_difference(cpu, opencl), "") << "OpenCL against the CPU";
            EXPECT_EQ(first_difference(cpu, vulkan), "") << "Vulkan against the CPU";
            std::size_t hits = 0, blended = 0;
            for (const appearance_pixel& p : cpu) hits += p.is_hit(), blended += p.visits > 1;
            EXPECT_GT(hits, s.rays.size() / 4);
            if (name == "opaque") {
                EXPECT_EQ(blended, 0u);  // every walk stops at its first voxel
                std::vector<hit> first(s.rays.size());
                tracer<cpu_scalar, S>(structure).closest_hit(s.rays, first);
                for (std::size_t i = 0; i < s.rays.size(); ++i) {
                    ASSERT_EQ(cpu[i].status, first[i].status) << i;
                    if (!first[i].is_hit()) continue;
                    ASSERT_EQ(glm::ivec3(cpu[i].x, cpu[i].y, cpu[i].z), first[i].voxel) << i;
                    ASSERT_EQ(cpu[i].t, first[i].t) << i;
                    ASSERT_EQ(cpu[i].material, first[i].material) << i;
                }
            } else {
                EXPECT_GT(blended, hits / 10);  // the tables are not opaque: walks go on
            }
        }
    });
}

// Several dispatches and a partly empty last group: more rays than one group, not a multiple of it.
TEST(appearance_walk_backends, ray_counts_that_are_not_a_multiple_of_the_group_agree) {
    VOXRAY_REQUIRE_DATA();
    const walk_scene& s = kitchen();
    std::vector<ray> rays(s.rays.begin(), s.rays.begin() + 777);
    const appearance_table& table = s.tables[1].second;
    dense_grid grid(s.model);
    using kernel = kernels::dense_grid_kernel;
    std::vector<appearance_pixel> cpu =
        appearance_walker<kernel, cpu_scalar>({grid.blob().begin(), grid.blob().end()}, table, 1).walk(rays, {});
    EXPECT_EQ(first_difference(cpu, appearance_walker<kernel>({grid.blob().begin(), grid.blob().end()}, table, 1)
                                        .walk(rays, {})), "") << "the SIMD lanes";
    vulkan_options through_staging;
    through_staging.force_staging = true;
    vulkan_appearance_walker<kernel> staged(grid.blob(), table, through_staging);
    EXPECT_EQ(first_difference(cpu, staged.walk(rays, {})), "") << "Vulkan through staging buffers";
    opencl_appearance_walker<kernel> opencl(grid.blob(), table);
    EXPECT_EQ(first_difference(cpu, opencl.walk(rays, {})), "");
    EXPECT_EQ(first_difference(cpu, opencl.walk(rays, {})), "") << "a second walk on the same walker";
    EXPECT_TRUE(opencl.walk({}, {}).empty());
}

// The compact records' lane code (cpu/appearance_samples.hpp) against the scalar lanes, bit
// for bit, on random records: 0 to 8 faces (all turned away in many lanes, which takes the
// second pass in some lanes only), any direction and light, and job counts that leave the
// last group partly empty. No data files needed.
TEST(appearance_walk_backends, compact_samples_on_simd_lanes_are_the_scalar_lanes_bit_for_bit) {
    namespace k = kernels::scalar;
    std::mt19937 random(25);
    auto bits = [&](unsigned n) { return std::uint32_t(random() & ((1ull << n) - 1)); };
    std::vector<std::uint32_t> records, faces;
    const std::uint32_t rows = 300;
    for (std::uint32_t row = 0; row < rows; ++row) {
        std::uint32_t first = std::uint32_t(faces.size() / VX_APP_FACE_WORDS), count = bits(16) % 9;
        records.push_back(first);
        records.push_back(count | bits(24) << 8);
        records.push_back(bits(28));
        for (std::uint32_t f = 0; f < count; ++f) faces.push_back(std::uint32_t(random())), faces.push_back(bits(32));
    }
    std::normal_distribution<float> normal;
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    auto direction = [&] {
        glm::vec3 d(normal(random), normal(random), normal(random));
        return glm::normalize(d);
    };
    for (std::size_t count : {1u, 7u, 8u, 9u, 16u, 33u, 1000u}) {
        cpu_detail::appearance_round round;
        round.fit(count);
        std::vector<k::vx_app_sample> want(count);
        for (std::size_t i = 0; i < count; ++i) {
            glm::vec3 d = direction(), l = direction() * unit(random);
            const std::uint32_t row = std::uint32_t(random() % rows);
            const k::vx_app_light light{l.x, l.y, l.z, unit(random)};
            round.set_job(i, row, d.x, d.y, d.z, light);
            want[i] = k::vx_app_compact_sample(records.data(), faces.data(), row, d.x, d.y, d.z, light);
        }
        const float nan = std::numeric_limits<float>::quiet_NaN();
        for (unsigned width : simd_widths()) {
            for (std::size_t i = 0; i < count; ++i) round.set_sample(i, {nan, nan, nan, nan, nan, nan, nan});
            cpu_detail::sample_lanes<VX_APP_KIND_COMPACT>(width, records.data(), faces.data(), round, count);
            for (std::size_t i = 0; i < count; ++i) {
                const k::vx_app_sample got = round.sample(i);
                ASSERT_EQ(std::memcmp(&want[i], &got, sizeof want[i]), 0)
                    << width << " lanes, job " << i << " of " << count << ": r " << want[i].r << " against "
                    << got.r << ", a " << want[i].a << " against " << got.a;
            }
        }
    }
}

}  // namespace
}  // namespace voxray
