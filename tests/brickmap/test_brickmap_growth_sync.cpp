// Growth without a whole upload: with the pool full, the first new brick doubles it;
// update() then sends the header and the new brick's words, not the whole blob, and the
// device's blob equals the host's word for word, on every backend (and on Vulkan through a
// staging copy too, as on a discrete GPU).
#include <gtest/gtest.h>

#include <cstdio>
#include <vector>

#include "every_backend.hpp"
#include "hit_bits.hpp"
#include "random_models.hpp"
#include "voxray/brickmap/brickmap.hpp"
#include "voxray/check/ray_sets.hpp"

namespace voxray {
namespace {

template <class Backend>
void pool_growth_sends_little(typename Backend::options options, const char* backend) {
    // Noise in one corner and a voxel in the far one: an empty world between them.
    voxel_model model = test::random_model(32, 0.1f, 3);
    model.set({127, 127, 127}, 5);
    brickmap<> m(model);
    m.shrink_to_fit();  // no spare bricks: the next new brick doubles the pool
    tracer<Backend, brickmap<>> t(m, options);
    std::size_t words_before = m.blob().size();
    std::uint32_t capacity_before = m.brick_capacity();

    for (int k = 0; k < 3; ++k) {
        m.fill_sphere({90 - 12 * k, 90, 90}, 3, std::uint8_t(7 + k));
        t.update(m);
        std::uint64_t sent = t.bytes_uploaded_last_update(), blob = m.blob().size_bytes();
        std::printf("[%s] update %d: %llu of %llu bytes sent\n", backend, k, (unsigned long long)sent,
                    (unsigned long long)blob);
        EXPECT_LT(sent * 8, blob) << backend << ", update " << k << ": the growth re-sent (nearly) the whole blob";
        auto device = t.engine().download_blob();
        ASSERT_EQ(device.size(), m.blob().size()) << backend;
        EXPECT_TRUE(std::equal(device.begin(), device.end(), m.blob().begin())) << backend << ": device and host differ";
    }
    EXPECT_GT(m.brick_capacity(), capacity_before) << "the pool should have grown";
    EXPECT_GT(m.blob().size(), words_before);

    // The grown blob traces as a fresh upload of the same words does.
    auto rays = check_rays(m.bounds(), 2, 5000, 31);
    std::vector<hit> grown(rays.size()), fresh(rays.size());
    t.closest_hit(rays, grown);
    tracer<Backend, brickmap<>>(std::as_const(m), options).closest_hit(rays, fresh);
    std::size_t differ = 0, hits = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) differ += !test::same_bits(grown[i], fresh[i]), hits += fresh[i].is_hit();
    EXPECT_EQ(differ, 0u) << backend;
    EXPECT_GT(hits, rays.size() / 100) << backend;  // a mostly empty world
}

template <class Backend>
struct BrickmapGrowthSyncOn : ::testing::Test {};
TYPED_TEST_SUITE(BrickmapGrowthSyncOn, test::every_backend, test::backend_names);

TYPED_TEST(BrickmapGrowthSyncOn, SendsLittle) { pool_growth_sends_little<TypeParam>({}, TypeParam::name); }

#if defined(VOXRAY_LINKED_VULKAN)
TEST(BrickmapGrowthSync, VulkanStaged) {
    vulkan_options options;
    options.force_staging = true;  // the old words copied device to device, as on a discrete GPU
    pool_growth_sends_little<vulkan>(options, "vulkan, staged");
}
#endif

}  // namespace
}  // namespace voxray
