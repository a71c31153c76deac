// Incremental device sync: after many random partial updates through
// tracer::update(Structure&), every backend's device blob equals the host's word for word,
// traces are bit-identical to a full upload of the same words, and the bytes sent are
// proportional to the dirty ranges (the commit packet: changed words plus a small table).
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "edited_grid.hpp"
#include "every_backend.hpp"
#include "random_models.hpp"
#include "voxray/core/type_list.hpp"
#include "voxray/sync/commit_packet.hpp"

// The portable commit kernel compiled as C++ (scalar lanes supply uint and vx_load).
namespace voxray::kernels::scalar {
#include "voxray/sync/commit.h"
}

namespace {

using namespace voxray;
using test::edit_kind;
using test::edited_grid;

// Every tracer backend this program links: the CPU always, the GPU ones when built (a
// missing device fails).
using backends = registered::backends;

edited_grid initial_grid() { return edited_grid(dense_grid(test::random_model(64, 0.02f, 7, {-9, 3, -30}))); }

// The first word where two blobs differ, or a note that they agree.
std::string first_difference(const std::vector<std::uint32_t>& device, const std::vector<std::uint32_t>& host) {
    if (device.size() != host.size())
        return "device has " + std::to_string(device.size()) + " words, host " + std::to_string(host.size());
    auto [a, b] = std::mismatch(device.begin(), device.end(), host.begin());
    if (a == device.end()) return "";
    return "word " + std::to_string(a - device.begin()) + ": device " + std::to_string(*a) + ", host " +
           std::to_string(*b);
}

template <class Tracer>
std::vector<hit> trace(Tracer& t, const std::vector<ray>& rays, bool any) {
    std::vector<hit> hits(rays.size());
    if (any) t.any_hit(rays, hits);
    else t.closest_hit(rays, hits);
    return hits;
}

std::size_t bit_differences(const std::vector<hit>& a, const std::vector<hit>& b) {
    std::size_t n = 0;
    for (std::size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(hit)) != 0;
    return n;
}

// The CPU backends (either lane kind) copy the changed words; the others send a packet.
template <class Backend>
constexpr bool copies_words = false;
template <bool Simd>
constexpr bool copies_words<cpu_backend<Simd>> = true;

// Bytes an update of `ranges` may send: the packed words (CPU: copied words), or the whole
// blob when the packet would not be smaller; never more than the ranges plus their table.
template <class Backend>
std::uint64_t expected_bytes(const std::vector<word_range>& ranges, std::uint32_t blob_words) {
    std::vector<word_range> merged = sync::normalize_ranges(ranges, blob_words);
    std::uint64_t words = sync::total_words(merged);
    if (merged.empty()) return 0;
    if constexpr (copies_words<Backend>) return words * 4;
    std::uint64_t packet = sync::packet_words(merged.size(), words);
    return 4 * (packet >= blob_words ? blob_words : packet);
}

template <class Backend>
void random_updates(typename Backend::options options, std::uint64_t seed, int steps) {
    edited_grid g = initial_grid();
    tracer<Backend, edited_grid> incremental(g, options);
    tracer<Backend, edited_grid> full(g, options);  // receives whole uploads only
    EXPECT_EQ(incremental.bytes_uploaded_last_update(), g.words.size() * 4);
    auto rays = random_rays(g.bounds, 3000, seed);
    auto more = check_rays(g.bounds, 2, 3000, seed + 1);
    rays.insert(rays.end(), more.begin(), more.end());

    rng r(seed);
    int ranges_seen = 0;
    for (int step = 0; step < steps; ++step) {
        // Every kind in the first rounds, then a random mix.
        auto kind = edit_kind(step < 2 * test::kinds_count ? step % test::kinds_count : r.below(test::kinds_count));
        std::vector<word_range> ranges = test::make_edit(g, r, kind);
        ranges_seen += int(ranges.size());
        std::uint64_t given = 0;
        for (auto& w : ranges) given += w.count;
        g.dirty = ranges;
        incremental.update(g);  // non-const: takes the dirty ranges
        EXPECT_TRUE(g.dirty.empty()) << "update did not take the dirty ranges";
        const std::string what = std::string(Backend::name) + " step " + std::to_string(step) + " (kind " +
                                 std::to_string(int(kind)) + ", " + std::to_string(ranges.size()) + " ranges)";

        std::uint64_t bytes = incremental.bytes_uploaded_last_update();
        EXPECT_EQ(bytes, expected_bytes<Backend>(ranges, g.size())) << what;
        EXPECT_LE(bytes, 4 * (given + VX_COMMIT_HEADER_WORDS + VX_COMMIT_RECORD_WORDS * ranges.size())) << what;
        if (kind == edit_kind::none) {
            EXPECT_EQ(bytes, 0u) << what;
        }

        auto device = incremental.engine().download_blob();
        ASSERT_EQ(first_difference(device, g.words), "") << what;

        if (step % 6 == 5 || step == steps - 1) {
            full.update(std::as_const(g));
            for (bool any : {false, true}) {
                auto a = trace(incremental, rays, any), b = trace(full, rays, any);
                EXPECT_EQ(bit_differences(a, b), 0u) << what << (any ? " any hit" : " closest hit");
            }
        }
    }
    EXPECT_GT(ranges_seen, 3000);
    // A tracer built from scratch on the final words agrees as well.
    tracer<Backend, edited_grid> fresh(std::as_const(g), options);
    EXPECT_EQ(bit_differences(trace(incremental, rays, false), trace(fresh, rays, false)), 0u);
}

template <class Backend>
struct sync_on : ::testing::Test {};
TYPED_TEST_SUITE(sync_on, test::every_backend, test::backend_names);

TYPED_TEST(sync_on, random_partial_updates) { random_updates<TypeParam>({}, 11, 60); }
#if defined(VOXRAY_LINKED_VULKAN)
TEST(sync, vulkan_staged_random_partial_updates) {
    vulkan_options options;
    options.force_staging = true;  // packet and blob through copy commands, as on a discrete GPU
    random_updates<vulkan>(options, 14, 40);
}
#endif

// A blob that changed size cannot be patched: the tracer sends it whole.
template <class Backend>
void size_change(typename Backend::options options) {
    edited_grid g = initial_grid();
    tracer<Backend, edited_grid> t(g, options);
    std::uint32_t old_size = g.size();
    g.words.resize(old_size + 100, 0xABCDu);  // trailing words the kernel never reads
    g.dirty = {{old_size, 100}};
    t.update(g);
    EXPECT_EQ(t.bytes_uploaded_last_update(), std::uint64_t(g.size()) * 4);
    EXPECT_EQ(first_difference(t.engine().download_blob(), g.words), "");
    // The engine checks too: update_ranges with another size uploads whole.
    g.words.resize(old_size);
    std::vector<word_range> one{{0, 1}};
    t.engine().update_ranges(g.blob(), one);
    EXPECT_EQ(t.bytes_uploaded_last_update(), std::uint64_t(old_size) * 4);
    EXPECT_EQ(first_difference(t.engine().download_blob(), g.words), "");
}

TEST(sync, size_change_uploads_whole_blob) {
    for_each_type(backends{}, []<class B>() { size_change<B>({}); });
}

// A range past the end of the blob is an error naming it, and changes nothing.
template <class Backend>
void bad_range(typename Backend::options options) {
    edited_grid g = initial_grid();
    tracer<Backend, edited_grid> t(g, options);
    g.dirty = {{g.size() - 4, 5}};
    EXPECT_THROW(t.update(g), voxray::error);
    EXPECT_EQ(first_difference(t.engine().download_blob(), g.words), "");
}

TEST(sync, range_past_end_is_an_error) {
    for_each_type(backends{}, []<class B>() { bad_range<B>({}); });
}

// The portable commit kernel as C++: every record type lands where it belongs.
TEST(sync, commit_kernel_as_cpp) {
    std::vector<std::uint32_t> source(5000), target(5000, 0);
    for (std::uint32_t i = 0; i < source.size(); ++i) source[i] = i * 2654435761u;
    std::vector<word_range> ranges{{4999, 1}, {0, 3}, {3, 2}, {100, 900}, {50, 60}, {2000, 1}, {2002, 1}};
    auto merged = sync::normalize_ranges(ranges, source.size());
    EXPECT_EQ(merged.size(), 5u);  // [0,5) [50,110) [100,1000) merge; 2000, 2002 stay apart; 4999
    sync::commit_packer packer;
    auto packet = packer.pack(source, merged);
    for (std::uint32_t i = 0; i < packet[VX_COMMIT_HEADER_DATA_WORDS] + 64; ++i)
        kernels::scalar::vx_commit_word(target.data(), packet.data(), i);
    for (std::uint32_t i = 0; i < source.size(); ++i) {
        bool dirty = std::any_of(ranges.begin(), ranges.end(),
                                 [&](word_range w) { return i >= w.offset && i < w.offset + w.count; });
        ASSERT_EQ(target[i], dirty ? source[i] : 0u) << "word " << i;
    }
}

// Not a pass/fail test: prints what a one-brick edit costs against a whole upload of a
// 64 MiB blob on each backend (8^3 voxels x 32-bit payload = 512 words).
template <class Backend>
void time_one_brick(typename Backend::options options) {
    edited_grid g = initial_grid();
    g.words.resize(std::size_t(16) << 20, 0u);  // padding the kernel never reads
    tracer<Backend, edited_grid> t(g, options);
    using clock = std::chrono::steady_clock;
    auto seconds = [](auto a, auto b) { return std::chrono::duration<double>(b - a).count(); };
    auto start = clock::now();
    t.update(std::as_const(g));
    double full = seconds(start, clock::now());
    rng r(5);
    std::vector<double> times;
    for (int i = 0; i < 21; ++i) {
        word_range brick{g.data_begin() + std::uint32_t(r.below(int(g.size() - g.data_begin() - 512))), 512};
        test::scramble(g, r, brick.offset, brick.count);
        g.dirty = {brick};
        start = clock::now();
        t.update(g);
        times.push_back(seconds(start, clock::now()));
    }
    std::nth_element(times.begin(), times.begin() + 10, times.end());
    std::printf("[timing] %-7s full upload of %zu MiB: %8.3f ms; one-brick update (%llu bytes sent): %8.3f ms "
                "(median of 21)\n",
                Backend::name, g.words.size() * 4 >> 20, full * 1e3,
                (unsigned long long)t.bytes_uploaded_last_update(), times[10] * 1e3);
    EXPECT_EQ(first_difference(t.engine().download_blob(), g.words), "");
}

TEST(sync, one_brick_update_timing) {
    for_each_type(backends{}, []<class B>() { time_one_brick<B>({}); });
#if defined(VOXRAY_LINKED_VULKAN)
    vulkan_options staged;
    staged.force_staging = true;
    time_one_brick<vulkan>(staged);
#endif
}

}  // namespace
