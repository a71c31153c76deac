// voxray in the application's own OpenCL context: this test creates the context, queue
// and buffers with the plain OpenCL API (as an engine would), builds tracers on them
// (opencl_options::user_context), traces rays that sit in its own cl_mem between commands
// of its own on the same queue, reads the hits back itself and compares them with the CPU
// tracer's. After the tracers are gone, the context and queue must have the reference
// counts the application gave them, and still work.
#include <CL/cl.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "hit_bits.hpp"
#include "random_models.hpp"
#include "scene_instances.hpp"
#include "voxray/brickmap/brickmap.hpp"
#include "voxray/check/ray_sets.hpp"
#include "voxray/cpu.hpp"
#include "voxray/entities/worlds/naadf.hpp"
#include "voxray/naadf/naadf.hpp"
#include "voxray/opencl.hpp"

using namespace voxray;

namespace {

void ok(cl_int status, const char* call) {
    if (status != CL_SUCCESS) fail(call, " failed: ", status);
}

// The application's side: created and released by the test, never by voxray.
struct app_context {
    cl_device_id device = nullptr;
    cl_context context = nullptr;
    cl_command_queue queue = nullptr;

    app_context() {
        cl_platform_id platform = nullptr;
        cl_uint n = 0;
        ok(clGetPlatformIDs(1, &platform, &n), "clGetPlatformIDs");
        if (n == 0) fail("no OpenCL platform (PoCL needs POCL_CACHE_DIR writable)");
        ok(clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 1, &device, &n), "clGetDeviceIDs");
        cl_int status = CL_SUCCESS;
        context = clCreateContext(nullptr, 1, &device, nullptr, nullptr, &status);
        ok(status, "clCreateContext");
        queue = clCreateCommandQueue(context, device, 0, &status);
        ok(status, "clCreateCommandQueue");
    }
    ~app_context() {
        clReleaseCommandQueue(queue);
        clReleaseContext(context);
    }
    app_context(const app_context&) = delete;
    app_context& operator=(const app_context&) = delete;

    opencl_options options() const {
        opencl_options o;
        o.user_context = opencl_user_context{context, device, queue};
        return o;
    }

    cl_mem buffer(std::size_t bytes) const {
        cl_int status = CL_SUCCESS;
        cl_mem m = clCreateBuffer(context, CL_MEM_READ_WRITE, bytes, nullptr, &status);
        ok(status, "clCreateBuffer");
        return m;
    }

    cl_uint context_references() const {
        cl_uint n = 0;
        ok(clGetContextInfo(context, CL_CONTEXT_REFERENCE_COUNT, sizeof n, &n, nullptr), "clGetContextInfo");
        return n;
    }
    cl_uint queue_references() const {
        cl_uint n = 0;
        ok(clGetCommandQueueInfo(queue, CL_QUEUE_REFERENCE_COUNT, sizeof n, &n, nullptr), "clGetCommandQueueInfo");
        return n;
    }
};

app_context& app() {
    static app_context c;
    return c;
}

constexpr unsigned char poison = 0xAB;

// The context and queue still work: a fill and a read on the application's queue.
void expect_context_usable() {
    cl_mem m = app().buffer(256);
    std::uint32_t pattern = 0x01020304u, word = 0;
    ok(clEnqueueFillBuffer(app().queue, m, &pattern, 4, 0, 256, 0, nullptr, nullptr), "clEnqueueFillBuffer");
    ok(clEnqueueReadBuffer(app().queue, m, CL_TRUE, 252, 4, &word, 0, nullptr, nullptr), "clEnqueueReadBuffer");
    clReleaseMemObject(m);
    EXPECT_EQ(word, pattern);
}

template <class Structure>
void traces_in_app_buffers(const Structure& s, const box3i& bounds) {
    auto rays = check_rays(bounds, 1, 3000, 23);
    std::vector<hit> expected(rays.size()), expected_any(rays.size());
    tracer<cpu, Structure> reference(s);
    reference.closest_hit(rays, expected);
    reference.any_hit(rays, expected_any);

    cl_uint context_refs = app().context_references(), queue_refs = app().queue_references();
    // Hits go to a sub-buffer, the documented way to an offset: the bytes around it must
    // keep the poison.
    cl_uint align_bits = 0;
    ok(clGetDeviceInfo(app().device, CL_DEVICE_MEM_BASE_ADDR_ALIGN, sizeof align_bits, &align_bits, nullptr),
       "clGetDeviceInfo");
    std::size_t offset = align_bits / 8, bytes = rays.size() * sizeof(hit);
    cl_mem in = app().buffer(rays.size() * sizeof(ray)), out = app().buffer(offset + bytes + 64);
    cl_buffer_region region{offset, bytes};
    cl_int status = CL_SUCCESS;
    cl_mem out_hits = clCreateSubBuffer(out, CL_MEM_READ_WRITE, CL_BUFFER_CREATE_TYPE_REGION, &region, &status);
    ok(status, "clCreateSubBuffer");
    ok(clEnqueueWriteBuffer(app().queue, in, CL_TRUE, 0, rays.size() * sizeof(ray), rays.data(), 0, nullptr, nullptr),
       "clEnqueueWriteBuffer");
    std::vector<unsigned char> got(offset + bytes + 64);
    auto run = [&](auto trace) {
        // Poison, trace and read back, all enqueued on the application's in-order queue
        // with no wait in between: its order alone must make this right.
        ok(clEnqueueFillBuffer(app().queue, out, &poison, 1, 0, got.size(), 0, nullptr, nullptr),
           "clEnqueueFillBuffer");
        trace();
        ok(clEnqueueReadBuffer(app().queue, out, CL_TRUE, 0, got.size(), got.data(), 0, nullptr, nullptr),
           "clEnqueueReadBuffer");
        std::size_t touched = 0;
        for (std::size_t i = 0; i < got.size(); ++i)
            touched += (i < offset || i >= offset + bytes) && got[i] != poison;
        EXPECT_EQ(touched, 0u) << "bytes outside the hits' sub-buffer changed";
        std::vector<hit> hits(rays.size());
        std::memcpy(hits.data(), got.data() + offset, bytes);
        return hits;
    };
    {
        tracer<opencl, Structure> t(s, app().options());
        std::vector<hit> hits = run([&] { t.closest_hit(in, out_hits, rays.size()); });
        std::size_t bad = 0, hit_count = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) {
            hit_count += expected[i].is_hit();
            if (!test::same_bits(hits[i], expected[i]) && ++bad <= 3)
                ADD_FAILURE() << "hit " << i << " is " << test::describe(hits[i]) << ", CPU "
                              << test::describe(expected[i]);
        }
        EXPECT_GT(hit_count, rays.size() / 10);
        EXPECT_EQ(bad, 0u) << "closest_hit on the application's buffers";

        hits = run([&] { t.any_hit(in, out_hits, rays.size()); });
        std::size_t bad_any = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) bad_any += hits[i].is_hit() != expected_any[i].is_hit();
        EXPECT_EQ(bad_any, 0u) << "any_hit on the application's buffers";

        // The host-array path in the same context.
        std::vector<hit> host(rays.size());
        t.closest_hit(rays, host);
        bad = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) bad += !test::same_bits(host[i], expected[i]);
        EXPECT_EQ(bad, 0u) << "closest_hit on host arrays";
    }
    for (cl_mem m : {out_hits, out, in}) clReleaseMemObject(m);
    // voxray let go of exactly what it took. PoCL's finished commands hold the queue for
    // a moment after they complete, so the counts get a second to settle.
    ok(clFinish(app().queue), "clFinish");
    for (int i = 0; i < 100 && (app().context_references() != context_refs || app().queue_references() != queue_refs);
         ++i)
        std::this_thread::sleep_for(std::chrono::milliseconds(10));
    EXPECT_EQ(app().context_references(), context_refs);
    EXPECT_EQ(app().queue_references(), queue_refs);
    expect_context_usable();
}

TEST(OpenclInterop, BrickmapInAppBuffers) { auto m = test::offset_random_scene(); traces_in_app_buffers(brickmap<>(m), m.bounds()); }
TEST(OpenclInterop, NaadfInAppBuffers) { auto m = test::offset_random_scene(); traces_in_app_buffers(naadf(m), m.bounds()); }

// Incremental updates go through the application's queue too: after an edit and update(),
// a trace on the application's buffers sees the new voxels.
TEST(OpenclInterop, UpdateOnAppQueue) {
    auto m = test::offset_random_scene();
    brickmap<> s(m);
    tracer<opencl, brickmap<>> t(s, app().options());
    s.apply(regions::sphere{{10, 20, -5}, 6}, edit_op::fill, 7);
    t.update(s);
    EXPECT_GT(t.bytes_uploaded_last_update(), 0u);

    auto rays = check_rays(m.bounds(), 1, 2000, 31);
    std::vector<hit> expected(rays.size()), got(rays.size());
    tracer<cpu, brickmap<>>(s).closest_hit(rays, expected);
    std::size_t edited = 0;
    for (const hit& h : expected) edited += h.is_hit() && h.material == 7;
    EXPECT_GT(edited, 10u) << "the edit should be in view of the rays";

    cl_mem in = app().buffer(rays.size() * sizeof(ray)), out = app().buffer(rays.size() * sizeof(hit));
    ok(clEnqueueWriteBuffer(app().queue, in, CL_FALSE, 0, rays.size() * sizeof(ray), rays.data(), 0, nullptr, nullptr),
       "clEnqueueWriteBuffer");
    t.closest_hit(in, out, rays.size());
    ok(clEnqueueReadBuffer(app().queue, out, CL_TRUE, 0, got.size() * sizeof(hit), got.data(), 0, nullptr, nullptr),
       "clEnqueueReadBuffer");
    clReleaseMemObject(in);
    clReleaseMemObject(out);
    std::size_t bad = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) bad += !test::same_bits(got[i], expected[i]);
    EXPECT_EQ(bad, 0u) << "closest_hit after an update";
}

template <class F>
std::string error_of(F f) {
    try {
        f();
    } catch (const voxray::error& e) {
        return e.what();
    }
    return "(no error)";
}

TEST(OpenclInterop, BadInputIsNamed) {
    auto m = test::offset_random_scene();
    brickmap<> s(m);
    auto bad_context = [&](auto change) {
        opencl_options o = app().options();
        change(*o.user_context);
        return error_of([&] { tracer<opencl, brickmap<>> t(s, o); });
    };
    std::string e = bad_context([](opencl_user_context& c) { c.queue = nullptr; });
    EXPECT_NE(e.find("opencl_user_context::queue is null"), std::string::npos) << e;

    // A second context: its queue does not belong to the first one.
    cl_int status = CL_SUCCESS;
    cl_context other = clCreateContext(nullptr, 1, &app().device, nullptr, nullptr, &status);
    ok(status, "clCreateContext");
    cl_command_queue other_queue = clCreateCommandQueue(other, app().device, 0, &status);
    ok(status, "clCreateCommandQueue");
    e = bad_context([&](opencl_user_context& c) { c.queue = other_queue; });
    EXPECT_NE(e.find("queue belongs to another context"), std::string::npos) << e;
    cl_command_queue unordered =
        clCreateCommandQueue(app().context, app().device, CL_QUEUE_OUT_OF_ORDER_EXEC_MODE_ENABLE, &status);
    if (status == CL_SUCCESS) {  // a device may refuse out-of-order queues altogether
        e = bad_context([&](opencl_user_context& c) { c.queue = unordered; });
        EXPECT_NE(e.find("queue is out of order"), std::string::npos) << e;
        clReleaseCommandQueue(unordered);
    }

    tracer<opencl, brickmap<>> t(s, app().options());
    cl_mem small = app().buffer(64), big = app().buffer(1024);
    cl_mem foreign = clCreateBuffer(other, CL_MEM_READ_WRITE, 1024, nullptr, &status);
    ok(status, "clCreateBuffer");
    e = error_of([&] { t.closest_hit(big, small, 4); });
    EXPECT_NE(e.find("4 hits need 128 bytes, but the hits buffer holds 64"), std::string::npos) << e;
    e = error_of([&] { t.closest_hit(foreign, big, 4); });
    EXPECT_NE(e.find("rays buffer belongs to another cl_context"), std::string::npos) << e;
    e = error_of([&] { t.any_hit(cl_mem(nullptr), big, 4); });
    EXPECT_NE(e.find("rays buffer is null"), std::string::npos) << e;
    for (cl_mem b : {small, big, foreign}) clReleaseMemObject(b);
    clReleaseCommandQueue(other_queue);
    clReleaseContext(other);
}

// A scene traces in two kernels (docs/design.md, "Staged kernels"): the second reads the
// hits the first wrote in the application's buffer.
TEST(OpenclInterop, SceneInAppBuffers) {
    auto m = test::offset_random_scene();
    naadf world(m);
    scene<naadf> s(world);
    test::add_test_instances(s, m.bounds(), 60);
    traces_in_app_buffers(s, m.bounds());
    // A hits buffer kernels may not read cannot take the second stage: refused, named.
    tracer<opencl, scene<naadf>> t(s, app().options());
    cl_int status = CL_SUCCESS;
    cl_mem rays = app().buffer(1024);
    cl_mem write_only = clCreateBuffer(app().context, CL_MEM_WRITE_ONLY, 1024, nullptr, &status);
    ok(status, "clCreateBuffer");
    std::string e = error_of([&] { t.closest_hit(rays, write_only, 4); });
    EXPECT_NE(e.find("the hits buffer is CL_MEM_WRITE_ONLY, but scene_naadf traces in two stages"), std::string::npos) << e;
    for (cl_mem b : {rays, write_only}) clReleaseMemObject(b);
}

}  // namespace
