// Vulkan device specifics (agreement with the CPU on every structure is tests/conformance):
// the device and its float rules on extreme and denormal directions, device selection
// errors, the staging path, update(), moves, batches larger than one dispatch, and a
// structure larger than maxStorageBufferRange (128 MiB on lavapipe).
//
// With no Vulkan device these tests fail (the engine throws); they never skip.
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "hit_bits.hpp"
#include "random_models.hpp"
#include "special_rays.hpp"
#include "voxray/check/compare.hpp"
#include "voxray/check/ray_sets.hpp"
#include "voxray/cpu.hpp"
#include "voxray/dense_grid/dense_grid.hpp"
#include "voxray/generated/structures.hpp"
#include "voxray/vulkan.hpp"

using namespace voxray;

namespace {

using gpu_tracer = tracer<vulkan, dense_grid>;
using cpu_tracer = tracer<cpu_scalar, dense_grid>;

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// ---- comparison -----------------------------------------------------------------------

struct outcome {
    agreement_counts counts;
    bool bit_identical = true;         // every byte of every hit, modulo the sign of a zero t
    std::uint64_t signed_zero_t = 0;   // hits with t = -0 on one side and +0 on the other
};

// Traces `rays` on both backends (closest or any hit) and compares ray by ray.
outcome compare(gpu_tracer& gpu, cpu_tracer& cpu, const std::vector<ray>& rays, bool any = false) {
    std::vector<hit> a(rays.size()), b(rays.size());
    if (any) {
        gpu.any_hit(rays, a);
        cpu.any_hit(rays, b);
    } else {
        gpu.closest_hit(rays, a);
        cpu.closest_hit(rays, b);
    }
    outcome o;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        o.bit_identical = test::same_bits(a[i], b[i]) && o.bit_identical;
        o.signed_zero_t += test::differ_in_zero_sign(a[i], b[i]);
        agreement g = compare_hits(rays[i], b[i], a[i]);
        o.counts.add(g);
        if (g == agreement::mismatch && o.counts.mismatches <= 5)
            ADD_FAILURE() << "ray " << i << ": " << test::describe(rays[i]) << "\n  cpu    " << test::describe(b[i])
                          << "\n  vulkan " << test::describe(a[i]);
    }
    return o;
}

// ---- tests ----------------------------------------------------------------------------

TEST(vulkan, finds_a_device) {
    dense_grid grid;
    gpu_tracer t(grid);
    EXPECT_FALSE(t.engine().device_name().empty());
    std::printf("vulkan device: %s (API %s), pipeline created in %.1f ms\n", t.engine().device_name().c_str(),
                vulkan_detail::version_string(t.engine().device_properties().apiVersion).c_str(),
                t.engine().pipeline_seconds() * 1e3);
}

// Rays on grid planes and corners (-0 and +0 included), with tiny or huge direction
// components (1/d near the float limits): the GPU must follow the C++ kernel's float rules.
void check_extreme(std::span<const float> components) {
    box3i b{{-8, -8, -8}, {8, 8, 8}};
    dense_grid grid(test::random_sparse(b, 800, 37));
    gpu_tracer gpu(grid);
    cpu_tracer cpu(grid);
    outcome o = compare(gpu, cpu, test::extreme_rays(b, components, 20000, 41));
    EXPECT_EQ(o.counts.mismatches, 0u);
    // On a CPU device (lavapipe) the float rules are the C++ kernel's, bit for bit.
    if (gpu.engine().device_properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) {
        EXPECT_TRUE(o.bit_identical);
    }
    std::printf("%llu rays: %llu same, %llu ties%s\n", (unsigned long long)o.counts.rays,
                (unsigned long long)o.counts.same, (unsigned long long)o.counts.ties,
                o.bit_identical ? ", bit-identical" : ", NOT bit-identical");
}

TEST(vulkan, extreme_directions_agree_with_cpu) { check_extreme(test::huge_and_tiny_components); }

// Denormal components (|d| < 2^-126, so 1/d = inf) count as zero (kernels/dda.h treats
// |d| < 7.52316385e-37 so), whether or not the device flushes denormals: no 0 * inf = NaN
// exit time that would stall the walk, on a cell plane or elsewhere.
TEST(vulkan, denormal_directions_agree_with_cpu) { check_extreme(test::denormal_components); }

TEST(vulkan, update_replaces_the_structure) {
    dense_grid a(test::hollow_box(16)), b(test::patterned_block({2, 2, 2}, {7, 7, 7}));
    gpu_tracer gpu(a);
    cpu_tracer cpu_a(a), cpu_b(b);
    auto rays = random_rays(a.bounds(), 5000, 11);
    std::vector<hit> before(rays.size()), after(rays.size()), expect(rays.size());
    gpu.closest_hit(rays, before);
    gpu.update(b);
    gpu.closest_hit(rays, after);
    cpu_b.closest_hit(rays, expect);
    std::size_t changed = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        changed += std::memcmp(&before[i], &after[i], sizeof(hit)) != 0;
        EXPECT_NE(compare_hits(rays[i], expect[i], after[i]), agreement::mismatch) << "ray " << i;
    }
    EXPECT_GT(changed, rays.size() / 4);
    gpu.update(a);  // smaller than the buffer now: reuses it
    EXPECT_EQ(compare(gpu, cpu_a, rays).counts.mismatches, 0u);
}

TEST(vulkan, staging_path_matches_direct_path) {
    dense_grid grid(test::random_sparse({{-10, 0, 10}, {30, 40, 50}}, 4000, 5));
    vulkan_options staging;
    staging.force_staging = true;
    gpu_tracer direct(grid), staged(grid, staging);
    cpu_tracer cpu(grid);
    auto rays = test::mixed_rays(grid.bounds(), 10000, 13);
    std::vector<hit> a(rays.size()), b(rays.size());
    direct.closest_hit(rays, a);
    staged.closest_hit(rays, b);
    EXPECT_TRUE(staged.engine().uses_staging());
    EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(hit)), 0);
    EXPECT_EQ(compare(staged, cpu, rays).counts.mismatches, 0u);
    std::printf("direct path on %s: %s\n", direct.engine().device_name().c_str(),
                direct.engine().uses_staging() ? "staged (no host-visible device memory)" : "mapped");
}

// The device time of the trace dispatches (timestamps) is there, and no more than the
// whole call that held them, also across several submissions (it is their sum).
TEST(vulkan, kernel_time_is_measured_per_trace) {
    dense_grid grid(test::hollow_box(20));
    gpu_tracer gpu(grid);
    for (std::size_t n : {std::size_t(5000), vulkan_detail::max_slice_rays + 1000}) {
        auto rays = random_rays(grid.bounds(), n, 23);
        std::vector<hit> hits(n);
        auto start = std::chrono::steady_clock::now();
        gpu.closest_hit(rays, hits);
        double wall = seconds_since(start), kernel = gpu.engine().kernel_seconds_last_trace();
        EXPECT_TRUE(std::isfinite(kernel)) << n << " rays";
        EXPECT_GT(kernel, 0.0) << n << " rays";
        EXPECT_LE(kernel, wall) << n << " rays";
    }
}

// A workgroup size from the options (a specialization constant) or VOXRAY_GROUP_SIZE traces
// the same hits; one that is not a power of two is refused, naming it.
TEST(vulkan, workgroup_size_is_an_option) {
    dense_grid grid(test::random_sparse({{-10, 0, 10}, {30, 40, 50}}, 4000, 5));
    auto rays = test::mixed_rays(grid.bounds(), 10001, 31);
    gpu_tracer standard(grid);
    EXPECT_EQ(standard.engine().work_group_size(), vulkan_detail::group_size);
    std::vector<hit> a(rays.size()), b(rays.size());
    standard.closest_hit(rays, a);
    for (std::uint32_t size : {1u, 32u, 256u}) {
        vulkan_options options;
        options.group_size = size;
        gpu_tracer sized(grid, options);
        EXPECT_EQ(sized.engine().work_group_size(), size);
        std::fill(b.begin(), b.end(), hit{});
        sized.closest_hit(rays, b);
        EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(hit)), 0) << "group size " << size;
    }
    vulkan_options odd;
    odd.group_size = 48;
    try {
        gpu_tracer refused(grid, odd);
        ADD_FAILURE() << "a workgroup size of 48 was accepted";
    } catch (const voxray::error& e) {
        EXPECT_NE(std::string(e.what()).find("group_size is 48"), std::string::npos) << e.what();
    }
    ::setenv("VOXRAY_GROUP_SIZE", "128", 1);
    gpu_tracer from_environment(grid);
    ::unsetenv("VOXRAY_GROUP_SIZE");
    EXPECT_EQ(from_environment.engine().work_group_size(), 128u);
}

TEST(vulkan, tracers_move) {
    dense_grid a(test::hollow_box(12)), b(test::patterned_block({0, 0, 0}, {4, 4, 4}));
    gpu_tracer first(a), second(b);
    gpu_tracer moved = std::move(first);
    second = std::move(moved);  // `second`'s old device objects are released in order
    ray r{{6.5f, 6.5f, -3.0f}, 0.0f, {0, 0, 1}, INFINITY};
    hit h;
    second.closest_hit({&r, 1}, {&h, 1});
    EXPECT_TRUE(h.is_hit());
    EXPECT_EQ(h.voxel, glm::ivec3(6, 6, 0));
}

// Tracers of every registered structure share one VkDevice (and the process one
// VkInstance); it is destroyed when the last of them goes. Their hits stay exact, also
// when they trace at once from several threads (one queue, submitted under a lock).
TEST(vulkan, tracers_of_every_structure_share_one_device) {
    voxel_model model = test::random_model(24, 0.3f, 29);
    auto rays = test::mixed_rays(model.bounds(), 2000, 3);
    std::vector<hit> expected(rays.size());
    tracer<cpu_scalar, dense_grid>(dense_grid(model)).closest_hit(rays, expected);
    std::weak_ptr<vulkan_detail::context> shared;
    {
        std::vector<VkDevice> devices;
        std::vector<std::function<void()>> traces;
        std::vector<std::shared_ptr<void>> keep;
        for_each_type(registered::structures{}, [&]<class S>() {
            auto structure = std::make_shared<S>(model);
            auto t = std::make_shared<tracer<vulkan, S>>(*structure);
            devices.push_back(t->engine().device());
            traces.push_back([t, &rays, &expected, name = std::string(S::name)] {
                std::vector<hit> got(rays.size());
                t->closest_hit(rays, got);
                std::size_t differ = 0;
                for (std::size_t i = 0; i < rays.size(); ++i) {
                    if constexpr (requires { S::material_is_colour; }) got[i].material = expected[i].material;  // RGBA, not an index
                    differ += compare_hits(rays[i], expected[i], got[i]) == agreement::mismatch;
                }
                EXPECT_EQ(differ, 0u) << name;
            });
            keep.push_back(structure);
            keep.push_back(t);
        });
        ASSERT_GE(devices.size(), 5u);
        for (VkDevice d : devices) EXPECT_EQ(d, devices.front()) << "a tracer made a VkDevice of its own";
        shared = vulkan_detail::shared_context({});
        EXPECT_EQ(shared.lock()->device(), devices.front());
        std::vector<std::thread> threads;
        for (auto& trace : traces) threads.emplace_back(trace);
        for (auto& thread : threads) thread.join();
    }
    EXPECT_TRUE(shared.expired()) << "the device outlived its last tracer";
}

// A structure beyond the device's limits fails with the numbers, before any allocation.
TEST(vulkan, oversized_buffer_is_a_clear_error) {
    auto shared = vulkan_detail::shared_context(vulkan_options{});
    const vulkan_detail::context& ctx = *shared;
    VkDeviceSize huge = VkDeviceSize(1) << 50;
    try {
        vulkan_detail::buffer b(ctx, huge, vulkan_detail::buffer_role::storage_upload, true, "structure blob");
        FAIL() << "a 1 PiB buffer was created";
    } catch (const voxray::error& e) {
        std::string what = e.what();
        EXPECT_NE(what.find(std::to_string(huge)), std::string::npos) << what;
        EXPECT_NE(what.find("maxMemoryAllocationSize"), std::string::npos) << what;
    }
}

TEST(vulkan, device_selection_by_name) {
    dense_grid grid;
    vulkan_options missing;
    missing.device = "no such device, surely";
    EXPECT_THROW(gpu_tracer(grid, missing), voxray::error);
    try {
        gpu_tracer t(grid, missing);
    } catch (const voxray::error& e) {
        EXPECT_NE(std::string(e.what()).find("no such device, surely"), std::string::npos) << e.what();
    }
    // The environment variable applies when the options name no device.
    const char* old = std::getenv("VOXRAY_VULKAN_DEVICE");
    std::string saved = old ? old : "";
    ::setenv("VOXRAY_VULKAN_DEVICE", "nothing matches this", 1);
    EXPECT_THROW(gpu_tracer{grid}, voxray::error);
    std::string name;
    {
        ::unsetenv("VOXRAY_VULKAN_DEVICE");
        gpu_tracer t(grid);
        name = t.engine().device_name();
    }
    vulkan_options named;
    named.device = name;
    gpu_tracer by_name(grid, named);
    EXPECT_EQ(by_name.engine().device_name(), name);
    if (old) ::setenv("VOXRAY_VULKAN_DEVICE", saved.c_str(), 1);
}

TEST(vulkan, batches_larger_than_one_submission) {
    dense_grid grid(test::hollow_box(20));
    gpu_tracer gpu(grid);
    cpu_tracer cpu(grid);
    std::size_t n = vulkan_detail::max_slice_rays + 1000;  // two submissions
    auto rays = random_rays(grid.bounds(), n, 17);
    outcome o = compare(gpu, cpu, rays);
    EXPECT_EQ(o.counts.mismatches, 0u);
    EXPECT_EQ(o.counts.rays, n);
}

// 35937 voxels, one per 16^3 chunk (spaced 16 apart): 35937 chunk records of 4.5 KiB make
// a 166 MiB blob, above lavapipe's 128 MiB maxStorageBufferRange. Rays aimed at voxels
// whose records lie past 128 MiB prove the shader reads them (by device address).
TEST(vulkan, structure_larger_than_max_storage_buffer_range) {
    auto start = std::chrono::steady_clock::now();
    constexpr int n = 33;
    std::vector<glm::ivec3> voxels;
    dense_grid grid;
    {
        voxel_model m;
        rng g(23);
        for (int z = 0; z < n; ++z)
            for (int y = 0; y < n; ++y)
                for (int x = 0; x < n; ++x) {
                    glm::ivec3 p = glm::ivec3(x, y, z) * 16 + glm::ivec3(g.below(16), g.below(16), g.below(16));
                    if (x + y + z == 0) p = {0, 0, 0};  // pin the bounds to whole chunks
                    if (x + y + z == 3 * (n - 1)) p = glm::ivec3(n * 16 - 1);
                    m.set(p, std::uint8_t(1 + (x + 3 * y + 7 * z) % 255));
                    voxels.push_back(p);
                }
        grid.build(m);
    }
    const std::uint64_t limit = 128ull << 20;
    ASSERT_GT(grid.bytes(), limit);
    gpu_tracer gpu(grid);
    cpu_tracer cpu(grid);
    std::printf("blob %.1f MiB, device maxStorageBufferRange %.1f MiB\n", grid.bytes() / 1048576.0,
                gpu.engine().device_properties().limits.maxStorageBufferRange / 1048576.0);

    // One ray from outside the box at each of 20000 voxels, aimed at its centre.
    rng g(29);
    std::vector<ray> rays;
    for (int i = 0; i < 20000; ++i) {
        glm::vec3 target = glm::vec3(voxels[std::size_t(g.below(int(voxels.size())))]) + 0.5f;
        glm::vec3 from(g.uniform(-50.0f, 600.0f), g.uniform(-50.0f, 600.0f), -40.0f);
        rays.push_back({from, 0.0f, glm::normalize(target - from), INFINITY});
    }
    std::vector<hit> a(rays.size()), b(rays.size());
    gpu.closest_hit(rays, a);
    cpu.closest_hit(rays, b);

    // Which hits came from chunk records past the 128 MiB mark?
    auto words = grid.blob();
    glm::uvec3 chunks(words[VX_DG_HEADER_CHUNKS], words[VX_DG_HEADER_CHUNKS + 1], words[VX_DG_HEADER_CHUNKS + 2]);
    std::size_t far = 0, hits = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        ASSERT_NE(compare_hits(rays[i], b[i], a[i]), agreement::mismatch) << "ray " << i;
        if (!a[i].is_hit()) continue;
        ++hits;
        glm::uvec3 c = glm::uvec3(a[i].voxel - grid.bounds().min) / 16u;
        std::uint64_t entry = words[words[VX_DG_HEADER_TABLE] + c.x + c.y * chunks.x + c.z * chunks.x * chunks.y];
        std::uint64_t byte = (words[VX_DG_HEADER_DATA] + entry * VX_DG_CHUNK_WORDS) * 4;
        far += byte >= limit;
    }
    EXPECT_GT(hits, rays.size() * 9 / 10);
    EXPECT_GT(far, 1000u);
    std::printf("%zu hits, %zu of them in chunk records past 128 MiB; %.1f s\n", hits, far, seconds_since(start));
}

// Not a benchmark (see `voxray bench`): prints the time of 1M random rays on a ~100k
// voxel model so that the report has a number.
TEST(vulkan, timing_one_million_rays) {
    dense_grid grid(test::sphere_shell(89));
    auto rays = random_rays(grid.bounds(), 1u << 20, 31);
    std::vector<hit> a(rays.size()), b(rays.size());
    auto start = std::chrono::steady_clock::now();
    gpu_tracer gpu(grid);
    double setup = seconds_since(start);
    gpu.closest_hit(rays, a);  // warm-up: allocates the ray and hit buffers
    start = std::chrono::steady_clock::now();
    gpu.closest_hit(rays, a);
    double t_gpu = seconds_since(start);
    cpu_tracer cpu(grid);
    start = std::chrono::steady_clock::now();
    cpu.closest_hit(rays, b);
    double t_cpu = seconds_since(start);
    outcome o = compare(gpu, cpu, rays);
    EXPECT_EQ(o.counts.mismatches, 0u);
    std::printf("%llu voxels, %zu rays on %s: engine setup %.0f ms (pipeline %.0f ms), trace %.3f s = %.2f Mrays/s; "
                "cpu-scalar %.3f s = %.2f Mrays/s; %llu ties\n",
                (unsigned long long)grid.voxel_count(), rays.size(), gpu.engine().device_name().c_str(), setup * 1e3,
                gpu.engine().pipeline_seconds() * 1e3, t_gpu, rays.size() / t_gpu / 1e6, t_cpu,
                rays.size() / t_cpu / 1e6, (unsigned long long)o.counts.ties);
}

}  // namespace
