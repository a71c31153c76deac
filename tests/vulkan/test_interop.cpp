// voxray on the application's own Vulkan device: this test creates the instance, device,
// queue and buffers with the plain Vulkan API (as an engine would), builds tracers on them
// (vulkan_options::user_device), traces rays that sit in its own buffers, both by the
// waiting call and by recording into its own command buffer, reads the hits back itself and
// compares them with the CPU tracer's. The device must stay usable after every tracer is gone.
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>
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
#include "voxray/vulkan.hpp"

using namespace voxray;

namespace {

void ok(VkResult r, const char* call) {
    if (r != VK_SUCCESS) fail(call, " failed: ", int(r));
}

template <class T>
T zeroed(VkStructureType type, void* next = nullptr) {
    T s{};
    s.sType = type;
    s.pNext = next;
    return s;
}

// The application's side: everything here is created and destroyed by the test, never by voxray.
struct app_device {
    VkInstance instance = VK_NULL_HANDLE;
    VkPhysicalDevice physical = VK_NULL_HANDLE;
    VkDevice device = VK_NULL_HANDLE;
    std::uint32_t family = 0;
    VkQueue queue = VK_NULL_HANDLE;
    VkCommandPool pool = VK_NULL_HANDLE;
    VkPhysicalDeviceMemoryProperties memory{};

    app_device() {
        auto app = zeroed<VkApplicationInfo>(VK_STRUCTURE_TYPE_APPLICATION_INFO);
        app.apiVersion = VK_API_VERSION_1_2;
        auto info = zeroed<VkInstanceCreateInfo>(VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO);
        info.pApplicationInfo = &app;
        ok(vkCreateInstance(&info, nullptr, &instance), "vkCreateInstance");
        std::uint32_t n = 1;
        VkResult r = vkEnumeratePhysicalDevices(instance, &n, &physical);  // the first one (lavapipe here)
        if ((r != VK_SUCCESS && r != VK_INCOMPLETE) || n == 0) fail("no Vulkan device");
        vkGetPhysicalDeviceMemoryProperties(physical, &memory);
        std::uint32_t families = 0;
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &families, nullptr);
        std::vector<VkQueueFamilyProperties> props(families);
        vkGetPhysicalDeviceQueueFamilyProperties(physical, &families, props.data());
        while (family < families && !(props[family].queueFlags & VK_QUEUE_COMPUTE_BIT)) ++family;
        if (family == families) fail("no compute queue");

        float priority = 1.0f;
        auto queue_info = zeroed<VkDeviceQueueCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO);
        queue_info.queueFamilyIndex = family;
        queue_info.queueCount = 1;
        queue_info.pQueuePriorities = &priority;
        auto v12 = zeroed<VkPhysicalDeviceVulkan12Features>(VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES);
        v12.bufferDeviceAddress = VK_TRUE;
        auto device_info = zeroed<VkDeviceCreateInfo>(VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &v12);
        device_info.queueCreateInfoCount = 1;
        device_info.pQueueCreateInfos = &queue_info;
        ok(vkCreateDevice(physical, &device_info, nullptr, &device), "vkCreateDevice");
        vkGetDeviceQueue(device, family, 0, &queue);
        auto pool_info = zeroed<VkCommandPoolCreateInfo>(VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO);
        pool_info.queueFamilyIndex = family;
        ok(vkCreateCommandPool(device, &pool_info, nullptr, &pool), "vkCreateCommandPool");
    }
    ~app_device() {
        vkDestroyCommandPool(device, pool, nullptr);
        vkDestroyDevice(device, nullptr);
        vkDestroyInstance(instance, nullptr);
    }
    app_device(const app_device&) = delete;
    app_device& operator=(const app_device&) = delete;

    vulkan_options options() const {
        vulkan_options o;
        o.user_device = vulkan_user_device{instance, physical, device, family, queue};
        return o;
    }

    // Records with `record`, submits on the application's queue and waits.
    template <class Record>
    void run(Record record) {
        auto alloc = zeroed<VkCommandBufferAllocateInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO);
        alloc.commandPool = pool;
        alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
        alloc.commandBufferCount = 1;
        VkCommandBuffer cmd = VK_NULL_HANDLE;
        ok(vkAllocateCommandBuffers(device, &alloc, &cmd), "vkAllocateCommandBuffers");
        auto begin = zeroed<VkCommandBufferBeginInfo>(VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO);
        ok(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
        record(cmd);
        ok(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
        auto fence_info = zeroed<VkFenceCreateInfo>(VK_STRUCTURE_TYPE_FENCE_CREATE_INFO);
        VkFence fence = VK_NULL_HANDLE;
        ok(vkCreateFence(device, &fence_info, nullptr, &fence), "vkCreateFence");
        auto submit = zeroed<VkSubmitInfo>(VK_STRUCTURE_TYPE_SUBMIT_INFO);
        submit.commandBufferCount = 1;
        submit.pCommandBuffers = &cmd;
        ok(vkQueueSubmit(queue, 1, &submit, fence), "vkQueueSubmit");
        ok(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
        vkDestroyFence(device, fence, nullptr);
        vkFreeCommandBuffers(device, pool, 1, &cmd);
    }
};

// A host-visible storage buffer with a device address, owned by the application.
struct app_buffer {
    VkDevice device;
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;

    app_buffer(const app_device& app, VkDeviceSize bytes) : device(app.device) {
        auto info = zeroed<VkBufferCreateInfo>(VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO);
        info.size = bytes;
        info.usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_SHADER_DEVICE_ADDRESS_BIT |
                     VK_BUFFER_USAGE_TRANSFER_DST_BIT;
        ok(vkCreateBuffer(device, &info, nullptr, &buffer), "vkCreateBuffer");
        VkMemoryRequirements req;
        vkGetBufferMemoryRequirements(device, buffer, &req);
        constexpr VkMemoryPropertyFlags host = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        std::uint32_t type = 0;
        while (type < app.memory.memoryTypeCount &&
               !((req.memoryTypeBits >> type & 1) && (app.memory.memoryTypes[type].propertyFlags & host) == host))
            ++type;
        if (type == app.memory.memoryTypeCount) fail("no host-visible memory (lavapipe has it)");
        auto flags = zeroed<VkMemoryAllocateFlagsInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_FLAGS_INFO);
        flags.flags = VK_MEMORY_ALLOCATE_DEVICE_ADDRESS_BIT;
        auto alloc = zeroed<VkMemoryAllocateInfo>(VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, &flags);
        alloc.allocationSize = req.size;
        alloc.memoryTypeIndex = type;
        ok(vkAllocateMemory(device, &alloc, nullptr, &memory), "vkAllocateMemory");
        ok(vkBindBufferMemory(device, buffer, memory, 0), "vkBindBufferMemory");
        ok(vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &mapped), "vkMapMemory");
    }
    ~app_buffer() {
        vkDestroyBuffer(device, buffer, nullptr);
        vkFreeMemory(device, memory, nullptr);
    }
    app_buffer(const app_buffer&) = delete;
    app_buffer& operator=(const app_buffer&) = delete;

    unsigned char* bytes() const { return static_cast<unsigned char*>(mapped); }
};

// One device for the whole program: tracers come and go on it, and each test checks
// that it still works afterwards.
app_device& app() {
    static app_device device;
    return device;
}

constexpr unsigned char poison = 0xAB;
constexpr VkDeviceSize ray_offset = 64, hit_offset = 96;  // multiples of 16, not of 32 * n

std::vector<hit> read_hits(const app_buffer& b, std::size_t count) {
    std::vector<hit> hits(count);
    std::memcpy(hits.data(), b.bytes() + hit_offset, count * sizeof(hit));
    return hits;
}

// Hits equal the CPU's bit for bit (but for the sign of a zero t, see hit_bits.hpp), and
// the bytes around the hits' range are as the test left them.
void expect_hits(const app_buffer& out, const std::vector<hit>& expected, const char* what) {
    std::vector<hit> got = read_hits(out, expected.size());
    std::size_t bad = 0, hits = 0;
    for (std::size_t i = 0; i < expected.size(); ++i) {
        hits += expected[i].is_hit();
        if (!test::same_bits(got[i], expected[i]) && ++bad <= 3)
            ADD_FAILURE() << what << ": hit " << i << " is " << test::describe(got[i]) << ", CPU "
                          << test::describe(expected[i]);
    }
    EXPECT_GT(hits, expected.size() / 10) << what;
    EXPECT_EQ(bad, 0u) << what;
    std::size_t end = hit_offset + expected.size() * sizeof(hit);
    for (std::size_t i = 0; i < hit_offset; ++i) ASSERT_EQ(out.bytes()[i], poison) << what << ": byte " << i;
    for (std::size_t i = end; i < end + 64; ++i) ASSERT_EQ(out.bytes()[i], poison) << what << ": byte " << i;
}

// The device still works for the application: a copy on its queue, waited on.
void expect_device_usable() {
    ASSERT_EQ(vkDeviceWaitIdle(app().device), VK_SUCCESS);
    app_buffer b(app(), 256);
    std::memset(b.mapped, 0, 256);
    app().run([&](VkCommandBuffer cmd) { vkCmdFillBuffer(cmd, b.buffer, 0, 256, 0x01020304u); });
    std::uint32_t word = 0;
    std::memcpy(&word, b.bytes() + 252, 4);
    EXPECT_EQ(word, 0x01020304u);
}

template <class Structure>
void traces_in_app_buffers(const Structure& s, const box3i& bounds) {
    auto rays = check_rays(bounds, 1, 3000, 23);
    std::vector<hit> expected(rays.size()), expected_any(rays.size());
    tracer<cpu, Structure> reference(s);
    reference.closest_hit(rays, expected);
    reference.any_hit(rays, expected_any);

    VkDeviceSize bytes = rays.size() * sizeof(ray) + 256;
    app_buffer in(app(), bytes), out(app(), bytes);
    std::memcpy(in.bytes() + ray_offset, rays.data(), rays.size() * sizeof(ray));
    vulkan_buffer_range ray_range{in.buffer, ray_offset, rays.size() * sizeof(ray)};
    vulkan_buffer_range hit_range{out.buffer, hit_offset};
    {
        tracer<vulkan, Structure> t(s, app().options());
        EXPECT_EQ(t.engine().device_name(), [] {
            VkPhysicalDeviceProperties p;
            vkGetPhysicalDeviceProperties(app().physical, &p);
            return std::string(p.deviceName);
        }());

        // Waiting call: submitted on the application's queue.
        std::memset(out.mapped, poison, bytes);
        t.closest_hit(ray_range, hit_range, rays.size());
        expect_hits(out, expected, "closest_hit on device buffers");

        std::memset(out.mapped, poison, bytes);
        t.any_hit(ray_range, hit_range, rays.size());
        std::vector<hit> any = read_hits(out, rays.size());
        std::size_t bad_any = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) bad_any += any[i].is_hit() != expected_any[i].is_hit();
        EXPECT_EQ(bad_any, 0u) << "any_hit on device buffers";

        // Recorded into the application's command buffer between its own commands: the
        // fill is ordered before the trace and the trace before the host read by the
        // application's barriers, as vulkan/interop.hpp asks.
        std::memset(out.mapped, 0, bytes);
        app().run([&](VkCommandBuffer cmd) {
            vkCmdFillBuffer(cmd, out.buffer, 0, bytes, 0xABABABABu);
            auto b = zeroed<VkMemoryBarrier>(VK_STRUCTURE_TYPE_MEMORY_BARRIER);
            b.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
            b.dstAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
            vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 1, &b,
                                 0, nullptr, 0, nullptr);
            t.record_closest_hit(cmd, ray_range, hit_range, rays.size());
            b.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
            b.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
            vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &b, 0,
                                 nullptr, 0, nullptr);
        });
        expect_hits(out, expected, "record_closest_hit");

        // The host-array path on the same device.
        std::vector<hit> got(rays.size());
        t.closest_hit(rays, got);
        std::size_t bad = 0;
        for (std::size_t i = 0; i < rays.size(); ++i) bad += !test::same_bits(got[i], expected[i]);
        EXPECT_EQ(bad, 0u) << "closest_hit on host arrays";
    }
    expect_device_usable();
}

TEST(VulkanInterop, BrickmapInAppBuffers) { auto m = test::offset_random_scene(); traces_in_app_buffers(brickmap<>(m), m.bounds()); }
TEST(VulkanInterop, NaadfInAppBuffers) { auto m = test::offset_random_scene(); traces_in_app_buffers(naadf(m), m.bounds()); }
// A scene (world and entities) on the application's buffers.
TEST(VulkanInterop, SceneInAppBuffers) {
    auto m = test::offset_random_scene();
    naadf world(m);
    scene<naadf> s(world);
    test::add_test_instances(s, m.bounds(), 60);
    traces_in_app_buffers(s, m.bounds());
}

// Several tracers made and destroyed on one device, the last still tracing after the
// others are gone: nothing of theirs took the device with it.
TEST(VulkanInterop, TracersComeAndGo) {
    auto m = test::offset_random_scene();
    naadf s(m);
    auto rays = check_rays(m.bounds(), 1, 500, 5);
    std::vector<hit> expected(rays.size()), got(rays.size());
    tracer<cpu, naadf>(s).closest_hit(rays, expected);
    auto last = std::make_unique<tracer<vulkan, naadf>>(s, app().options());
    brickmap<> other(m);
    for (int i = 0; i < 3; ++i) {
        tracer<vulkan, brickmap<>> t(other, app().options());
    }
    last->closest_hit(rays, got);
    for (std::size_t i = 0; i < rays.size(); ++i) ASSERT_TRUE(test::same_bits(got[i], expected[i])) << i;
    last.reset();
    expect_device_usable();
}

// Staged uploads and incremental updates go through the application's queue too: after an
// edit and update(), a trace on the application's buffers sees the new voxels.
TEST(VulkanInterop, StagedUpdateOnAppQueue) {
    auto m = test::offset_random_scene();
    brickmap<> s(m);
    vulkan_options o = app().options();
    o.force_staging = true;
    tracer<vulkan, brickmap<>> t(s, o);
    EXPECT_TRUE(t.engine().uses_staging());
    s.apply(regions::sphere{{10, 20, -5}, 6}, edit_op::fill, 7);
    t.update(s);
    EXPECT_GT(t.bytes_uploaded_last_update(), 0u);

    auto rays = check_rays(m.bounds(), 1, 2000, 31);
    std::vector<hit> expected(rays.size());
    tracer<cpu, brickmap<>>(s).closest_hit(rays, expected);
    std::size_t edited = 0;
    for (const hit& h : expected) edited += h.is_hit() && h.material == 7;
    EXPECT_GT(edited, 10u) << "the edit should be in view of the rays";

    VkDeviceSize bytes = rays.size() * sizeof(ray) + 256;
    app_buffer in(app(), bytes), out(app(), bytes);
    std::memcpy(in.bytes() + ray_offset, rays.data(), rays.size() * sizeof(ray));
    std::memset(out.mapped, poison, bytes);
    t.closest_hit(vulkan_buffer_range{in.buffer, ray_offset}, vulkan_buffer_range{out.buffer, hit_offset}, rays.size());
    expect_hits(out, expected, "closest_hit after a staged update");
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

TEST(VulkanInterop, BadInputIsNamed) {
    auto m = test::offset_random_scene();
    brickmap<> s(m);
    auto bad_device = [&](auto change) {
        vulkan_options o = app().options();
        change(*o.user_device);
        return error_of([&] { tracer<vulkan, brickmap<>> t(s, o); });
    };
    EXPECT_NE(bad_device([](vulkan_user_device& d) { d.device = VK_NULL_HANDLE; }).find("::device is VK_NULL_HANDLE"),
              std::string::npos);
    EXPECT_NE(bad_device([](vulkan_user_device& d) { d.queue = VK_NULL_HANDLE; }).find("::queue is VK_NULL_HANDLE"),
              std::string::npos);
    EXPECT_NE(bad_device([](vulkan_user_device& d) { d.queue_family = 99; }).find("queue_family is 99"),
              std::string::npos);

    tracer<vulkan, brickmap<>> t(s, app().options());
    app_buffer in(app(), 1024), out(app(), 1024);
    std::string e = error_of([&] { t.closest_hit(vulkan_buffer_range{in.buffer, 8}, vulkan_buffer_range{out.buffer}, 4); });
    EXPECT_NE(e.find("rays offset is 8 bytes; it must be a multiple of 16"), std::string::npos) << e;
    e = error_of([&] { t.closest_hit(vulkan_buffer_range{in.buffer}, vulkan_buffer_range{out.buffer, 0, 64}, 4); });
    EXPECT_NE(e.find("4 hits need 128 bytes, but the hits range holds 64"), std::string::npos) << e;
    e = error_of([&] { t.closest_hit(vulkan_buffer_range{in.buffer, 4096}, vulkan_buffer_range{out.buffer}, 1); });
    EXPECT_NE(e.find("past the end of the rays buffer"), std::string::npos) << e;
    e = error_of([&] { t.closest_hit(vulkan_buffer_range{}, vulkan_buffer_range{out.buffer}, 1); });
    EXPECT_NE(e.find("rays buffer is VK_NULL_HANDLE"), std::string::npos) << e;
    e = error_of([&] {
        t.record_closest_hit(VkCommandBuffer(VK_NULL_HANDLE), vulkan_buffer_range{in.buffer},
                             vulkan_buffer_range{out.buffer}, 1);
    });
    EXPECT_NE(e.find("needs a command buffer"), std::string::npos) << e;
}

}  // namespace
