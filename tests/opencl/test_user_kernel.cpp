// Tracing from the user's own OpenCL kernel: tests/opencl/user_kernel.cl includes the
// generated voxray/shaders/<name>.cl (the file `cmake --install` puts in include/) and calls
// vx_<name>_trace on a blob, rays and hits in buffers this test made with the plain OpenCL
// API, as a user's engine would. Its hits and flags must match the CPU tracer's.
#include <CL/cl.h>

#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "every_structure.hpp"
#include "hit_bits.hpp"
#include "random_models.hpp"
#include "voxray/check/ray_sets.hpp"
#include "voxray/cpu.hpp"
#include "voxray/opencl/device.hpp"
#include "voxray/opencl/error.hpp"
#include "voxray/opencl/handles.hpp"

using namespace voxray;
namespace ocl = voxray::opencl_detail;

namespace {

std::string read_text(const std::string& path) {
    std::ifstream in(path);
    if (!in) fail("cannot read ", path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

cl_mem make_buffer(cl_context ctx, cl_mem_flags flags, std::size_t bytes, const void* data) {
    cl_int status = 0;
    cl_mem m = clCreateBuffer(ctx, flags | (data ? CL_MEM_COPY_HOST_PTR : 0), bytes, const_cast<void*>(data), &status);
    ocl::check(status, "clCreateBuffer");
    return m;
}

// `other`: a structure whose traversal the program includes first, as a program tracing
// several would (the one called is then the second include).
template <class Structure>
void user_kernel_matches_cpu(const Structure& s, const box3i& bounds, const std::string& other) {
    auto rays = check_rays(bounds, 1, 4000, 17);
    std::vector<hit> expected(rays.size()), expected_any(rays.size());
    tracer<cpu, Structure> reference(s);
    reference.closest_hit(rays, expected);
    reference.any_hit(rays, expected_any);

    // The user's side: device, context, queue, program, buffers.
    ocl::device_choice dev = ocl::select_device({});
    cl_int status = 0;
    ocl::context_handle ctx(clCreateContext(nullptr, 1, &dev.device, nullptr, nullptr, &status));
    ocl::check(status, "clCreateContext");
    ocl::queue_handle queue(clCreateCommandQueue(ctx.get(), dev.device, 0, &status));
    ocl::check(status, "clCreateCommandQueue");
    std::string name = Structure::kernel::name;
    std::string source = "#define USER_TRACE vx_" + name + "_trace\n#include \"voxray/shaders/" + other +
                         ".cl\"\n#include \"voxray/shaders/" + name + ".cl\"\n" + read_text(VOXRAY_USER_KERNEL);
    const char* text = source.c_str();
    ocl::program_handle program(clCreateProgramWithSource(ctx.get(), 1, &text, nullptr, &status));
    ocl::check(status, "clCreateProgramWithSource");
    std::string options = "-cl-std=CL1.2 -cl-fp32-correctly-rounded-divide-sqrt -I " VOXRAY_SHADER_INCLUDE_DIR;
    if (clBuildProgram(program.get(), 1, &dev.device, options.c_str(), nullptr, nullptr) != CL_SUCCESS) {
        std::size_t size = 0;
        clGetProgramBuildInfo(program.get(), dev.device, CL_PROGRAM_BUILD_LOG, 0, nullptr, &size);
        std::string log(size, '\0');
        clGetProgramBuildInfo(program.get(), dev.device, CL_PROGRAM_BUILD_LOG, size, log.data(), nullptr);
        FAIL() << "the user kernel did not build:\n" << log;
    }
    cl_kernel kernel = clCreateKernel(program.get(), "user_trace", &status);
    ocl::check(status, "clCreateKernel");

    auto blob = s.blob();
    cl_mem blob_buf = make_buffer(ctx.get(), CL_MEM_READ_ONLY, blob.size_bytes(), blob.data());
    cl_mem ray_buf = make_buffer(ctx.get(), CL_MEM_READ_ONLY, rays.size() * sizeof(ray), rays.data());
    cl_mem hit_buf = make_buffer(ctx.get(), CL_MEM_WRITE_ONLY, rays.size() * sizeof(hit), nullptr);
    cl_mem flag_buf = make_buffer(ctx.get(), CL_MEM_WRITE_ONLY, rays.size() * sizeof(std::uint32_t), nullptr);
    cl_uint count = cl_uint(rays.size());
    clSetKernelArg(kernel, 0, sizeof(cl_mem), &blob_buf);
    clSetKernelArg(kernel, 1, sizeof(cl_mem), &ray_buf);
    clSetKernelArg(kernel, 2, sizeof(cl_mem), &hit_buf);
    clSetKernelArg(kernel, 3, sizeof(cl_mem), &flag_buf);
    clSetKernelArg(kernel, 4, sizeof(cl_uint), &count);
    std::size_t global = (rays.size() + 63) / 64 * 64, local = 64;
    ocl::check(clEnqueueNDRangeKernel(queue.get(), kernel, 1, nullptr, &global, &local, 0, nullptr, nullptr),
               "clEnqueueNDRangeKernel");
    std::vector<hit> got(rays.size());
    std::vector<std::uint32_t> blocked(rays.size());
    ocl::check(clEnqueueReadBuffer(queue.get(), hit_buf, CL_TRUE, 0, got.size() * sizeof(hit), got.data(), 0, nullptr, nullptr),
               "clEnqueueReadBuffer");
    ocl::check(clEnqueueReadBuffer(queue.get(), flag_buf, CL_TRUE, 0, blocked.size() * 4, blocked.data(), 0, nullptr, nullptr),
               "clEnqueueReadBuffer");
    for (cl_mem m : {blob_buf, ray_buf, hit_buf, flag_buf}) clReleaseMemObject(m);
    clReleaseKernel(kernel);

    std::size_t hits = 0, bad = 0, bad_flags = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        hits += expected[i].is_hit();
        bad += !test::same_bits(got[i], expected[i]);
        bad_flags += blocked[i] != (expected_any[i].is_hit() ? 1u : 0u);
    }
    EXPECT_GT(hits, rays.size() / 10);
    EXPECT_EQ(bad, 0u) << name << ": hits from the user's kernel differ from the CPU tracer's";
    EXPECT_EQ(bad_flags, 0u) << name << ": any-hit flags from the user's kernel differ";
}

template <class Structure>
struct UserKernelOn : ::testing::Test {};
TYPED_TEST_SUITE(UserKernelOn, test::every_structure, test::structure_names);

// Another structure's traversal goes in first, as in a program that traces several.
TYPED_TEST(UserKernelOn, MatchesTheCpuTracer) {
    auto m = test::offset_random_scene();
    std::string name = TypeParam::kernel::name;
    user_kernel_matches_cpu(TypeParam(m), m.bounds(), name == "dense_grid" ? "svdag" : "dense_grid");
}

}  // namespace
