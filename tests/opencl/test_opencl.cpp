// OpenCL device specifics (agreement with the CPU on every structure is tests/conformance):
// the device and its program, update() growing and shrinking the buffer, ray buffers
// reused across batch sizes, one program per structure built once, and errors that name
// the device, the call and the limits. With correctly rounded division (PoCL) hits must
// be cpu_scalar's bit for bit; without, they must still agree with no ties.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include "hit_bits.hpp"
#include "random_models.hpp"
#include "special_rays.hpp"
#include "voxray/check/compare.hpp"
#include "voxray/check/ray_sets.hpp"
#include "voxray/cpu.hpp"
#include "voxray/opencl.hpp"
#include "voxray/dense_grid/dense_grid.hpp"

namespace {

using namespace voxray;

// ---- comparison ----------------------------------------------------------------------

template <class Backend>
std::vector<hit> trace_with(tracer<Backend, dense_grid>& t, const std::vector<ray>& rays, std::uint32_t mode) {
    std::vector<hit> hits(rays.size());
    if (mode == VX_MODE_ANY) t.any_hit(rays, hits);
    else t.closest_hit(rays, hits);
    return hits;
}

// Compares OpenCL hits with the scalar CPU reference: no mismatches, no ties, and
// bit-identical records when the device divides with correct rounding.
agreement_counts expect_agreement(const std::string& what, const std::vector<ray>& rays, const std::vector<hit>& reference,
                      const std::vector<hit>& tested, bool exact) {
    agreement_counts counts;
    std::size_t different_bits = 0, reported = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        counts.add(compare_hits(rays[i], reference[i], tested[i]));
        if (!test::identical(reference[i], tested[i])) {
            ++different_bits;
            if (reported++ < 5)
                ADD_FAILURE() << what << ": ray " << i << " " << test::describe(rays[i])
                              << "\n  cpu:    " << test::describe(reference[i])
                              << "\n  opencl: " << test::describe(tested[i]);
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

// ---- tests ---------------------------------------------------------------------------

TEST(opencl, device_is_found_and_program_builds) {
    // No GTEST_SKIP anywhere: CI must have a device (PoCL), so its absence fails here.
    dense_grid grid(test::single_voxel({0, 0, 0}));
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

// The trace kernels' device time (profiling events) is there, and no more than the call.
TEST(opencl, kernel_time_is_measured_per_trace) {
    dense_grid grid(test::hollow_box(20));
    tracer<opencl, dense_grid> gpu(grid);
    auto rays = random_rays(grid.bounds(), 20000, 23);
    std::vector<hit> hits(rays.size());
    auto start = std::chrono::steady_clock::now();
    gpu.closest_hit(rays, hits);
    double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    double kernel = gpu.engine().kernel_seconds_last_trace();
    EXPECT_TRUE(std::isfinite(kernel));
    EXPECT_GT(kernel, 0.0);
    EXPECT_LE(kernel, wall);
}

// A work-group size from the options or VOXRAY_GROUP_SIZE traces the same hits; one that
// is not a power of two is refused, naming it.
TEST(opencl, work_group_size_is_an_option) {
    dense_grid grid(test::random_sparse({{0, 0, 0}, {30, 30, 30}}, 2000, 5));
    auto rays = test::mixed_rays(grid.bounds(), 10001, 31);
    tracer<opencl, dense_grid> standard(grid);
    auto expected = trace_with(standard, rays, VX_MODE_CLOSEST);
    for (std::size_t size : {1u, 32u, 128u}) {
        opencl_options options;
        options.group_size = size;
        tracer<opencl, dense_grid> sized(grid, options);
        EXPECT_EQ(sized.engine().work_group_size(), size);
        auto got = trace_with(sized, rays, VX_MODE_CLOSEST);
        for (std::size_t i = 0; i < rays.size(); ++i)
            ASSERT_TRUE(test::identical(expected[i], got[i])) << "group size " << size << ", ray " << i;
    }
    opencl_options odd;
    odd.group_size = 48;
    try {
        tracer<opencl, dense_grid> refused(grid, odd);
        ADD_FAILURE() << "a work-group size of 48 was accepted";
    } catch (const voxray::error& e) {
        EXPECT_NE(std::string(e.what()).find("group_size is 48"), std::string::npos) << e.what();
    }
    ::setenv("VOXRAY_GROUP_SIZE", "16", 1);
    tracer<opencl, dense_grid> from_environment(grid);
    ::unsetenv("VOXRAY_GROUP_SIZE");
    EXPECT_EQ(from_environment.engine().work_group_size(), 16u);
}

TEST(opencl, update_replaces_the_structure) {
    dense_grid small(test::patterned_block({0, 0, 0}, {4, 4, 4}));
    dense_grid big(test::hollow_box(box3i{{-10, -10, -10}, {30, 30, 30}}));  // a larger blob: the buffer must grow
    ASSERT_GT(big.blob().size(), small.blob().size());
    tracer<opencl, dense_grid> gpu(small);
    auto rays = test::mixed_rays(big.bounds(), 10000, 99);
    auto before = trace_with(gpu, rays, VX_MODE_CLOSEST);

    gpu.update(big);
    auto after = trace_with(gpu, rays, VX_MODE_CLOSEST);
    tracer<cpu_scalar, dense_grid> cpu(big);
    expect_agreement("after update", rays, trace_with(cpu, rays, VX_MODE_CLOSEST), after,
                     gpu.engine().correctly_rounded_division());
    std::size_t changed = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) changed += !test::identical(before[i], after[i]);
    EXPECT_GT(changed, rays.size() / 4);

    // And back to the smaller blob, which now sits in a larger buffer.
    gpu.engine().update(small.blob());
    tracer<cpu_scalar, dense_grid> cpu_small(small);
    expect_agreement("after shrinking update", rays, trace_with(cpu_small, rays, VX_MODE_CLOSEST),
                     trace_with(gpu, rays, VX_MODE_CLOSEST), gpu.engine().correctly_rounded_division());
}

TEST(opencl, ray_buffers_are_reused_across_sizes) {
    dense_grid grid(test::random_sparse({{0, 0, 0}, {30, 30, 30}}, 2000, 5));
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
    dense_grid grid(test::single_voxel({1, 2, 3}));
    tracer<opencl, dense_grid> a(grid);
    tracer<opencl, dense_grid> b(grid);
    auto ctx1 = opencl_detail::acquire_device_context({});
    auto ctx2 = opencl_detail::acquire_device_context({});
    EXPECT_EQ(ctx1.get(), ctx2.get());
    EXPECT_EQ(a.engine().program_build_seconds(), b.engine().program_build_seconds());
    EXPECT_EQ(a.engine().program_build_seconds(), ctx1->build_seconds("dense_grid"));
    // The program is built once and then handed out again, the same object each time.
    auto program = opencl_detail::find_program("dense_grid");
    EXPECT_EQ(ctx1->program(program), ctx2->program(program));
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
    dense_grid grid(test::single_voxel({1, 2, 3}));
    tracer<opencl, dense_grid> t(grid);
    std::vector<ray> rays{ray{{1.5f, 2.5f, -5.0f}, 0.0f, {0.0f, 0.0f, 1.0f}, INFINITY}};
    std::vector<hit> hits(1);
    t.closest_hit(rays, hits);
    EXPECT_TRUE(hits[0].is_hit());
}

TEST(opencl, selecting_a_missing_device_names_what_exists) {
    dense_grid grid(test::single_voxel({0, 0, 0}));
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
