// The OpenCL backend against the scalar CPU backend: the same portable kernel, so with
// correctly rounded division (PoCL) every hit record must be bit-identical — t, voxel,
// face, material, step count and status. Where the device lacks correctly rounded
// division, hits must still agree under compare_hits with no ties.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "voxray/check/compare.hpp"
#include "voxray/check/ray_sets.hpp"
#include "voxray/cpu.hpp"
#include "voxray/opencl.hpp"
#include "voxray/dense_grid/dense_grid.hpp"

namespace {

using namespace voxray;

// ---- models ------------------------------------------------------------------------

voxel_model random_sparse(glm::ivec3 lo, glm::ivec3 hi, int count, std::uint64_t seed) {
    voxel_model m;
    rng g(seed);
    for (int i = 0; i < count; ++i) {
        glm::ivec3 p(lo.x + g.below(hi.x - lo.x), lo.y + g.below(hi.y - lo.y), lo.z + g.below(hi.z - lo.z));
        m.set(p, std::uint8_t(1 + g.below(255)));
    }
    return m;
}

voxel_model solid_block(glm::ivec3 lo, glm::ivec3 hi) {
    voxel_model m;
    for (int z = lo.z; z < hi.z; ++z)
        for (int y = lo.y; y < hi.y; ++y)
            for (int x = lo.x; x < hi.x; ++x) m.set({x, y, z}, std::uint8_t(1 + (x + 3 * y + 7 * z) % 200));
    return m;
}

voxel_model hollow_box(glm::ivec3 lo, glm::ivec3 hi) {
    voxel_model m;
    for (int z = lo.z; z < hi.z; ++z)
        for (int y = lo.y; y < hi.y; ++y)
            for (int x = lo.x; x < hi.x; ++x) {
                bool shell = x == lo.x || y == lo.y || z == lo.z || x == hi.x - 1 || y == hi.y - 1 || z == hi.z - 1;
                if (shell) m.set({x, y, z}, std::uint8_t(1 + (x * 5 + y + z * 11) % 250));
            }
    return m;
}

voxel_model single_voxel(glm::ivec3 p) {
    voxel_model m;
    m.set(p, 42);
    return m;
}

struct named_model {
    std::string name;
    voxel_model model;
};

std::vector<named_model> models() {
    std::vector<named_model> out;
    out.push_back({"random_sparse", random_sparse({0, 0, 0}, {40, 40, 40}, 3000, 1)});
    out.push_back({"random_multi_chunk", random_sparse({0, 0, 0}, {70, 35, 50}, 6000, 2)});
    out.push_back({"solid_block", solid_block({0, 0, 0}, {20, 12, 8})});
    out.push_back({"hollow_box", hollow_box({3, 2, 1}, {27, 26, 25})});
    out.push_back({"single_voxel", single_voxel({5, 7, 9})});
    out.push_back({"negative_sparse", random_sparse({-60, -45, -33}, {-10, -5, -2}, 3000, 3)});
    out.push_back({"straddling_zero", random_sparse({-20, -17, -9}, {21, 14, 30}, 4000, 4)});
    out.push_back({"negative_hollow", hollow_box({-40, -30, -20}, {-18, -12, -1})});
    return out;
}

// ---- comparison ----------------------------------------------------------------------

std::vector<ray> rays_for(const box3i& bounds, std::uint64_t seed) {
    auto rays = random_rays(bounds, 20000, seed);
    auto check = check_rays(bounds, 2, 20000, seed + 100);
    rays.insert(rays.end(), check.begin(), check.end());
    return rays;
}

template <class Backend>
std::vector<hit> trace_with(tracer<Backend, dense_grid>& t, const std::vector<ray>& rays, std::uint32_t mode) {
    std::vector<hit> hits(rays.size());
    if (mode == VX_MODE_ANY) t.any_hit(rays, hits);
    else t.closest_hit(rays, hits);
    return hits;
}

bool bit_identical(const hit& a, const hit& b) { return std::memcmp(&a, &b, sizeof(hit)) == 0; }

std::string describe(const ray& r, const hit& h) {
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "ray o=(%.9g %.9g %.9g) d=(%.9g %.9g %.9g) tmin=%.9g tmax=%.9g -> t=%.9g voxel=(%d %d %d) face=%s "
                  "material=%u steps=%u status=%u",
                  r.origin.x, r.origin.y, r.origin.z, r.direction.x, r.direction.y, r.direction.z, r.tmin, r.tmax,
                  h.t, h.voxel.x, h.voxel.y, h.voxel.z, face_name(h.normal), h.material, h.steps, h.status);
    return buf;
}

// Compares OpenCL hits with the scalar CPU reference: no mismatches, no ties, and
// bit-identical records when the device divides with correct rounding.
agreement_counts expect_agreement(const std::string& what, const std::vector<ray>& rays, const std::vector<hit>& reference,
                      const std::vector<hit>& tested, bool exact) {
    agreement_counts counts;
    std::size_t different_bits = 0, reported = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        counts.add(compare_hits(rays[i], reference[i], tested[i]));
        if (!bit_identical(reference[i], tested[i])) {
            ++different_bits;
            if (reported++ < 5)
                ADD_FAILURE() << what << ": ray " << i << "\n  cpu:    " << describe(rays[i], reference[i])
                              << "\n  opencl: " << describe(rays[i], tested[i]);
        }
    }
    EXPECT_EQ(counts.mismatches, 0u) << what;
    EXPECT_EQ(counts.ties, 0u) << what;
    if (exact) {
        EXPECT_EQ(different_bits, 0u) << what << ": records not bit-identical";
    }
    EXPECT_EQ(counts.rays, rays.size());
    return counts;
}

std::size_t count_hits(const std::vector<hit>& hits) {
    std::size_t n = 0;
    for (auto& h : hits) n += h.is_hit();
    return n;
}

// ---- tests ---------------------------------------------------------------------------

TEST(opencl, device_is_found_and_program_builds) {
    // No GTEST_SKIP anywhere: CI must have a device (PoCL), so its absence fails here.
    dense_grid grid(single_voxel({0, 0, 0}));
    tracer<opencl, dense_grid> t(grid);
    auto& e = t.engine();
    EXPECT_FALSE(e.device_name().empty());
    EXPECT_GE(e.work_group_size(), 1u);
    EXPECT_GT(e.max_alloc_bytes(), 0u);
    std::printf("[opencl] platform '%s', device '%s', program build %.3f s, work-group %zu, "
                "correctly rounded division: %s\n",
                e.platform_name().c_str(), e.device_name().c_str(), e.program_build_seconds(), e.work_group_size(),
                e.correctly_rounded_division() ? "yes" : "no");
}

TEST(opencl, agrees_with_cpu_scalar_on_every_model) {
    std::uint64_t seed = 10;
    for (auto& [name, model] : models()) {
        dense_grid grid(model);
        tracer<opencl, dense_grid> gpu(grid);
        tracer<cpu_scalar, dense_grid> cpu(grid);
        bool exact = gpu.engine().correctly_rounded_division();
        auto rays = rays_for(grid.bounds(), seed++);
        for (std::uint32_t mode : {VX_MODE_CLOSEST, VX_MODE_ANY}) {
            auto reference = trace_with(cpu, rays, mode);
            auto tested = trace_with(gpu, rays, mode);
            std::string what = name + (mode == VX_MODE_ANY ? " (any hit)" : " (closest hit)");
            auto counts = expect_agreement(what, rays, reference, tested, exact);
            std::printf("[opencl] %-32s %zu voxels: %llu rays, %zu hits, same %llu, ties %llu, mismatches %llu\n",
                        what.c_str(), std::size_t(grid.voxel_count()), (unsigned long long)counts.rays,
                        count_hits(reference), (unsigned long long)counts.same, (unsigned long long)counts.ties,
                        (unsigned long long)counts.mismatches);
            // Guard against a vacuous pass: most models must actually be hit.
            if (name != "single_voxel") {
                EXPECT_GT(count_hits(reference), rays.size() / 20) << name;
            }
        }
    }
}

// Rays from every lattice point of a box slightly larger than the model, in all 26
// directions of {-1,0,1}^3: origins exactly on faces, edges and corners, rays running
// along faces and through edges — where a sign of zero or a NaN rule could differ.
TEST(opencl, lattice_rays_are_bit_identical) {
    voxel_model model = hollow_box({0, 0, 0}, {6, 5, 4});
    model.set({2, 2, 2}, 77);  // something inside the shell, for rays that start within it
    dense_grid grid(model);
    std::vector<ray> rays;
    for (int z = -1; z <= 5; ++z)
        for (int y = -1; y <= 6; ++y)
            for (int x = -1; x <= 7; ++x)
                for (int d = 0; d < 27; ++d) {
                    glm::vec3 dir(d % 3 - 1, d / 3 % 3 - 1, d / 9 - 1);
                    if (dir == glm::vec3(0.0f)) continue;
                    rays.push_back(ray{glm::vec3(x, y, z), 0.0f, dir, std::numeric_limits<float>::infinity()});
                    rays.push_back(ray{glm::vec3(x, y, z) + 0.5f, 0.25f, dir, 3.0f});
                }
    tracer<opencl, dense_grid> gpu(grid);
    tracer<cpu_scalar, dense_grid> cpu(grid);
    auto reference = trace_with(cpu, rays, VX_MODE_CLOSEST);
    auto counts = expect_agreement("lattice", rays, reference, trace_with(gpu, rays, VX_MODE_CLOSEST),
                                   gpu.engine().correctly_rounded_division());
    EXPECT_GT(count_hits(reference), rays.size() / 10);
    std::printf("[opencl] lattice rays: %llu rays, %zu hits, same %llu, ties %llu, mismatches %llu\n",
                (unsigned long long)counts.rays, count_hits(reference), (unsigned long long)counts.same,
                (unsigned long long)counts.ties, (unsigned long long)counts.mismatches);
}

TEST(opencl, empty_model_misses_everything) {
    dense_grid grid{voxel_model{}};
    tracer<opencl, dense_grid> gpu(grid);
    tracer<cpu_scalar, dense_grid> cpu(grid);
    auto rays = random_rays(box3i{{-4, -4, -4}, {4, 4, 4}}, 2000, 7);
    auto tested = trace_with(gpu, rays, VX_MODE_CLOSEST);
    EXPECT_EQ(count_hits(tested), 0u);
    expect_agreement("empty", rays, trace_with(cpu, rays, VX_MODE_CLOSEST), tested,
                     gpu.engine().correctly_rounded_division());
}

TEST(opencl, invalid_rays_miss) {
    dense_grid grid(solid_block({0, 0, 0}, {8, 8, 8}));
    tracer<opencl, dense_grid> gpu(grid);
    const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
    // Each of these points straight at the block, so only the invalid field makes it miss.
    ray good{{-5.0f, 4.5f, 4.5f}, 0.0f, {1.0f, 0.0f, 0.0f}, inf};
    std::vector<ray> rays(9, good);
    rays[1].origin.y = nan;
    rays[2].direction.x = nan;
    rays[3].tmin = nan;
    rays[4].tmax = nan;
    rays[5].origin.x = -inf;
    rays[6].direction = glm::vec3(0.0f);
    rays[7].tmin = 3.0f, rays[7].tmax = 2.0f;
    rays[8].direction.z = inf;
    std::vector<hit> hits(rays.size());
    gpu.closest_hit(rays, hits);
    ASSERT_TRUE(hits[0].is_hit());
    EXPECT_EQ(hits[0].voxel, glm::ivec3(0, 4, 4));
    EXPECT_EQ(hits[0].normal, face::neg_x);
    EXPECT_FLOAT_EQ(hits[0].t, 5.0f);
    for (std::size_t i = 1; i < rays.size(); ++i) {
        EXPECT_EQ(hits[i].status, VX_STATUS_MISS) << "ray " << i;
        EXPECT_EQ(hits[i].normal, face::none) << "ray " << i;
        EXPECT_TRUE(std::isinf(hits[i].t)) << "ray " << i;
    }
}

TEST(opencl, update_replaces_the_structure) {
    dense_grid small(solid_block({0, 0, 0}, {4, 4, 4}));
    dense_grid big(hollow_box({-10, -10, -10}, {30, 30, 30}));  // a larger blob: the buffer must grow
    ASSERT_GT(big.blob().size(), small.blob().size());
    tracer<opencl, dense_grid> gpu(small);
    auto rays = rays_for(big.bounds(), 99);
    auto before = trace_with(gpu, rays, VX_MODE_CLOSEST);

    gpu.update(big);
    auto after = trace_with(gpu, rays, VX_MODE_CLOSEST);
    tracer<cpu_scalar, dense_grid> cpu(big);
    expect_agreement("after update", rays, trace_with(cpu, rays, VX_MODE_CLOSEST), after,
                     gpu.engine().correctly_rounded_division());
    std::size_t changed = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) changed += !bit_identical(before[i], after[i]);
    EXPECT_GT(changed, rays.size() / 4);

    // And back to the smaller blob, which now sits in a larger buffer.
    gpu.engine().update(small.blob());
    tracer<cpu_scalar, dense_grid> cpu_small(small);
    expect_agreement("after shrinking update", rays, trace_with(cpu_small, rays, VX_MODE_CLOSEST),
                     trace_with(gpu, rays, VX_MODE_CLOSEST), gpu.engine().correctly_rounded_division());
}

TEST(opencl, ray_buffers_are_reused_across_sizes) {
    dense_grid grid(random_sparse({0, 0, 0}, {30, 30, 30}, 2000, 5));
    tracer<opencl, dense_grid> gpu(grid);
    tracer<cpu_scalar, dense_grid> cpu(grid);
    // Odd sizes exercise the rounded-up global size (items past `count` must not write).
    for (std::size_t n : {1000u, 7u, 1u, 5003u, 64u, 65u}) {
        auto rays = random_rays(grid.bounds(), n, n);
        std::vector<hit> hits(n + 3);  // extra room must stay untouched
        hit sentinel;
        sentinel.material = 12345;
        for (auto& h : hits) h = sentinel;
        gpu.closest_hit(rays, hits);
        std::vector<hit> tested(hits.begin(), hits.begin() + n);
        expect_agreement("batch of " + std::to_string(n), rays, trace_with(cpu, rays, VX_MODE_CLOSEST), tested,
                         gpu.engine().correctly_rounded_division());
        for (std::size_t i = n; i < hits.size(); ++i) EXPECT_EQ(hits[i].material, 12345u);
    }
    std::vector<hit> none;
    gpu.closest_hit(std::span<const ray>{}, none);  // zero rays: nothing to do
    std::vector<ray> two(2);
    std::vector<hit> one(1);
    EXPECT_THROW(gpu.closest_hit(two, one), voxray::error);
}

TEST(opencl, program_is_built_once_per_device) {
    dense_grid grid(single_voxel({1, 2, 3}));
    tracer<opencl, dense_grid> a(grid);
    tracer<opencl, dense_grid> b(grid);
    auto ctx1 = opencl_detail::acquire_device_context({});
    auto ctx2 = opencl_detail::acquire_device_context({});
    EXPECT_EQ(ctx1.get(), ctx2.get());
    EXPECT_EQ(a.engine().program_build_seconds(), b.engine().program_build_seconds());
    EXPECT_EQ(a.engine().program_build_seconds(), ctx1->build_seconds("dense_grid"));
    EXPECT_GT(ctx1->build_seconds("dense_grid"), 0.0);
}

// Each structure is its own program: one that does not build fails with its name and the
// build log, and the other structures keep working on the same device.
TEST(opencl, a_broken_program_breaks_only_its_structure) {
    auto ctx = opencl_detail::acquire_device_context({});
    opencl_detail::program_source broken{"broken_toy", "__kernel void vx_closest_broken_toy( { no such syntax"};
    try {
        ctx->program(broken);
        FAIL() << "expected a build error";
    } catch (const opencl_error& e) {
        EXPECT_NE(std::string(e.what()).find("broken_toy"), std::string::npos) << e.what();
    }
    dense_grid grid(single_voxel({1, 2, 3}));
    tracer<opencl, dense_grid> t(grid);
    std::vector<ray> rays{ray{{1.5f, 2.5f, -5.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, INFINITY}};
    std::vector<hit> hits(1);
    t.closest_hit(rays, hits);
    EXPECT_TRUE(hits[0].is_hit());
}

TEST(opencl, selecting_a_missing_device_names_what_exists) {
    dense_grid grid(single_voxel({0, 0, 0}));
    opencl_options options;
    options.device = "no-such-device-xyzzy";
    try {
        tracer<opencl, dense_grid> t(grid, options);
        FAIL() << "expected an error";
    } catch (const opencl_error& e) {
        std::string what = e.what();
        EXPECT_NE(what.find("no-such-device-xyzzy"), std::string::npos) << what;
        // The message lists the devices that do exist, e.g. PoCL's.
        auto any = opencl_detail::select_device({});
        EXPECT_NE(what.find(any.device_name), std::string::npos) << what;
    }
}

TEST(opencl, alloc_limit_check_names_both_numbers) {
    using opencl_detail::check_alloc_limit;
    EXPECT_NO_THROW(check_alloc_limit("the structure blob", 1000, 1000, "fake device"));
    try {
        check_alloc_limit("the structure blob", 3'000'000'000ull, 1'073'741'824ull, "fake device");
        FAIL() << "expected an error";
    } catch (const voxray::error& e) {
        std::string what = e.what();
        EXPECT_NE(what.find("3000000000"), std::string::npos) << what;
        EXPECT_NE(what.find("1073741824"), std::string::npos) << what;
        EXPECT_NE(what.find("CL_DEVICE_MAX_MEM_ALLOC_SIZE"), std::string::npos) << what;
        EXPECT_NE(what.find("fake device"), std::string::npos) << what;
    }
}

TEST(opencl, cl_errors_name_the_call_and_status) {
    try {
        opencl_detail::check(CL_OUT_OF_RESOURCES, "clEnqueueNDRangeKernel", "tracing 5 rays");
        FAIL() << "expected an error";
    } catch (const opencl_error& e) {
        std::string what = e.what();
        EXPECT_EQ(e.code(), CL_OUT_OF_RESOURCES);
        EXPECT_NE(what.find("clEnqueueNDRangeKernel"), std::string::npos) << what;
        EXPECT_NE(what.find("CL_OUT_OF_RESOURCES (-5)"), std::string::npos) << what;
        EXPECT_NE(what.find("tracing 5 rays"), std::string::npos) << what;
    }
    EXPECT_NO_THROW(opencl_detail::check(CL_SUCCESS, "clFinish"));
    EXPECT_STREQ(opencl_detail::cl_status_name(CL_INVALID_KERNEL_NAME), "CL_INVALID_KERNEL_NAME");
}

}  // namespace
