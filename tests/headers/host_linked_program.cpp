// A program that links voxray::kernels, as a user writes it: load a .vox, build NAADF,
// edit it, trace it on the CPU, OpenCL and Vulkan. Compiled, never run: host_linked.cmake
// reads its object file to check that the host code and the SIMD streams are only
// referenced here, compiled once in the library (core/host_code.hpp, cpu/lanes.hpp).
#include <filesystem>
#include <vector>

#include "voxray/cpu.hpp"
#include "voxray/io/vox_reader.hpp"
#include "voxray/naadf/naadf.hpp"
#include "voxray/opencl.hpp"
#include "voxray/rays.hpp"
#include "voxray/vulkan.hpp"

#if !defined(VOXRAY_HOST_LINKED) || VOXRAY_HOST_DEFINITIONS || VOXRAY_CPU_SIMD_LANES
#error "this file must see voxray::kernels' usage requirements (tests/headers/CMakeLists.txt)"
#endif

std::size_t host_linked_program(const std::filesystem::path& scene) {
    voxray::voxel_model model = voxray::io::load_vox(scene);
    voxray::naadf world(model);
    voxray::tracer<voxray::cpu, voxray::naadf> cpu(world);
    voxray::tracer<voxray::opencl, voxray::naadf> cl(world);
    voxray::tracer<voxray::vulkan, voxray::naadf> gpu(world);
    world.fill_sphere({8, 8, 8}, 4, 5);
    world.refine();
    cpu.update(world);
    cl.update(world);
    gpu.update(world);
    std::vector<voxray::ray> rays = voxray::primary_rays(voxray::auto_camera(model.bounds(), model.up_axis), 64, 64);
    std::vector<voxray::hit> a(rays.size()), b(rays.size()), c(rays.size());
    cpu.closest_hit(rays, a);
    cl.closest_hit(rays, b);
    gpu.closest_hit(rays, c);
    std::size_t same = 0;
    for (std::size_t i = 0; i < a.size(); ++i) same += a[i].t == b[i].t && a[i].t == c[i].t;
    return same;
}
