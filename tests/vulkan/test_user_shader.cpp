// Tracing from the user's own Vulkan compute shader: user_trace.comp.in includes the
// generated voxray/shaders/<name>.glsl (the file `cmake --install` puts in include/) and
// calls vx_<name>_trace on a blob, rays and hits in buffers this test owns. Its hits and
// flags must match the CPU tracer's. (The test borrows voxray's small Vulkan helpers for
// device, buffers and pipeline; an engine would use its own.)
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hit_bits.hpp"
#include "random_models.hpp"
#include "every_structure.hpp"
#include "voxray/check/ray_sets.hpp"
#include "voxray/cpu.hpp"
#include "voxray/vulkan.hpp"

using namespace voxray;
namespace vk = voxray::vulkan_detail;

namespace {

// Must match user_push in user_trace.comp.in (std430: uvec2 at 0, 8, 16, 24; count at 32).
struct user_push {
    std::uint64_t blob, rays, hits, flags;
    std::uint32_t count, unused[3];
};

std::vector<std::uint32_t> read_spirv(const std::string& path) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (!in) fail("cannot read ", path);
    std::vector<std::uint32_t> words(std::size_t(in.tellg()) / 4);
    in.seekg(0);
    in.read(reinterpret_cast<char*>(words.data()), std::streamsize(words.size() * 4));
    return words;
}

// A device buffer the host writes or reads directly (lavapipe maps every buffer).
vk::buffer mapped_buffer(const vk::context& ctx, std::size_t bytes, vk::buffer_role role, const void* data) {
    vk::buffer b(ctx, std::max<std::size_t>(bytes, 4), role, true, "user buffer");
    if (!b.mapped()) fail("this test needs host-visible device memory (lavapipe has it)");
    if (data) std::memcpy(b.mapped(), data, bytes);
    return b;
}

template <class Structure>
void user_shader_matches_cpu(const Structure& s, const box3i& bounds) {
    auto rays = check_rays(bounds, 1, 4000, 19);
    std::vector<hit> expected(rays.size()), expected_any(rays.size());
    tracer<cpu, Structure> reference(s);
    reference.closest_hit(rays, expected);
    reference.any_hit(rays, expected_any);

    std::string name = Structure::kernel::name;
    auto shared = vk::shared_context(vulkan_options{});
    const vk::context& ctx = *shared;
    vk::command_stream commands(ctx);
    auto spirv = read_spirv(std::string(VOXRAY_USER_SPIRV_DIR) + "/user_" + name + ".spv");
    vk::compute_pipeline pipeline(ctx, spirv, sizeof(user_push));
    auto blob = s.blob();
    vk::buffer blob_buf = mapped_buffer(ctx, blob.size_bytes(), vk::buffer_role::storage_upload, blob.data());
    vk::buffer ray_buf = mapped_buffer(ctx, rays.size() * sizeof(ray), vk::buffer_role::storage_upload, rays.data());
    vk::buffer hit_buf = mapped_buffer(ctx, rays.size() * sizeof(hit), vk::buffer_role::storage_readback, nullptr);
    vk::buffer flag_buf = mapped_buffer(ctx, rays.size() * 4, vk::buffer_role::storage_readback, nullptr);

    VkCommandBuffer cmd = commands.begin();
    user_push pc{blob_buf.address(), ray_buf.address(), hit_buf.address(), flag_buf.address(),
                 std::uint32_t(rays.size()), {}};
    pipeline.bind(cmd, pc);
    vkCmdDispatch(cmd, std::uint32_t((rays.size() + 63) / 64), 1, 1);
    vk::command_stream::barrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_ACCESS_SHADER_WRITE_BIT,
                                VK_PIPELINE_STAGE_HOST_BIT, VK_ACCESS_HOST_READ_BIT);
    commands.submit_and_wait();
    std::vector<hit> got(rays.size());
    std::vector<std::uint32_t> blocked(rays.size());
    std::memcpy(got.data(), hit_buf.mapped(), got.size() * sizeof(hit));
    std::memcpy(blocked.data(), flag_buf.mapped(), blocked.size() * 4);

    std::size_t hits = 0, bad = 0, bad_flags = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        hits += expected[i].is_hit();
        bad += !test::same_bits(got[i], expected[i]);
        bad_flags += blocked[i] != (expected_any[i].is_hit() ? 1u : 0u);
    }
    EXPECT_GT(hits, rays.size() / 10);
    EXPECT_EQ(bad, 0u) << name << ": hits from the user's shader differ from the CPU tracer's";
    EXPECT_EQ(bad_flags, 0u) << name << ": any-hit flags from the user's shader differ";
}

template <class Structure>
struct UserShaderOn : ::testing::Test {};
TYPED_TEST_SUITE(UserShaderOn, test::every_structure, test::structure_names);

TYPED_TEST(UserShaderOn, MatchesTheCpuTracer) {
    auto m = test::offset_random_scene();
    user_shader_matches_cpu(TypeParam(m), m.bounds());
}

}  // namespace
