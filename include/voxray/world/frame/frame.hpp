// A chunked world rendered by the GPU-driven passes (world/frame/passes.h, the paper's section
// 3.5) on any backend: the CPU runs the same pass functions on its thread pool.
//
//   voxray::tracer<voxray::vulkan, voxray::streamed_world> t(world);   // or chunked_world
//   voxray::world_frame<voxray::vulkan, voxray::streamed_world> frame(t);
//   frame_stats s = frame.render(voxray::frame_view(cam, 1280, 720, far), world.blob());
//   frame.materials();   // per pixel: the hit's attribute (0: no hit), as closest_hit's
//   frame.visibility();  // per pixel: the 64-bit visibility word (world/frame/layout.h)
//
// The frame buffer lives on the backend; render() writes its header, runs the passes one
// by one (each to completion, so the timings are per pass) and reads back only the
// counters that size the next pass. The Hi-Z of one render() culls the next one's tiles.
#pragma once
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <span>
#include <string_view>
#include <vector>

#include <glm/geometric.hpp>

#if !defined(VOXRAY_LINKED_CPU)
#error "voxray/world/frame/frame.hpp needs voxray::cpu (the passes' CPU path, and the scalar lanes it runs them on): link it"
#endif
#include "voxray/core/error.hpp"
#include "voxray/core/ray.hpp"
#include "voxray/cpu/lanes.hpp"
#include "voxray/rays/camera.hpp"
#include "voxray/tracer.hpp"
#include "voxray/world/frame/layout.h"
#include "voxray/world/world.hpp"

namespace voxray::kernels::scalar {
#include "voxray/world/frame/passes.h"
}  // namespace voxray::kernels::scalar

namespace voxray {

// The view the passes render (world/frame/layout.h): camera, unit forward, right and up
// scaled by the half-extent of the view, screen size and far plane. Hits' t are depths.
struct frame_view {
    glm::vec3 position{0.0f}, forward{0.0f, 0.0f, 1.0f}, right{1.0f, 0.0f, 0.0f}, up{0.0f, 1.0f, 0.0f};
    int width = 1, height = 1;
    float far_depth = 1e5f;

    frame_view() = default;
    frame_view(const camera& c, int width_px, int height_px, float far)
        : position(c.position), width(width_px), height(height_px), far_depth(far) {
        if (width_px <= 0 || height_px <= 0 || width_px > 16384 || height_px > 16384)
            fail("world frame: a screen of ", width_px, " x ", height_px, " pixels (each side 1..16384)");
        if (!(far > 0.0f)) fail("world frame: the far plane must be beyond the camera, not ", far);
        camera_frame cf(c, width_px, height_px);
        forward = cf.forward;
        right = cf.right * cf.half_w;
        up = cf.up * cf.half_h;
    }
};

// One render's counts and per-pass milliseconds (wall time, each pass run to completion;
// select_chunks includes the host's nearest-first sort of what it found).
struct frame_stats {
    // A frame's steps in order: tile selection, march and Hi-Z run a second time against
    // this frame's own Hi-Z (the tiles the previous one culled wrongly).
    enum step : std::size_t {
        clear, select_chunks, select_tiles, march, build_hiz, select_again, march_again, build_hiz_again, resolve, steps
    };
    static constexpr std::array<std::string_view, steps> pass_names{
        "clear", "select chunks", "select tiles", "march", "build hi-z", "select again", "march again",
        "build hi-z again", "resolve"};
    std::array<double, steps> ms{};
    std::uint32_t table_rows = 0, visible_chunks = 0, pairs = 0, pairs_again = 0;
    std::uint64_t frame_bytes = 0;  // the frame buffer on the device
    int restarts = 0;               // the pair list grew: the frame ran again from the start
    double total_ms() const {
        double t = 0;
        for (double m : ms) t += m;
        return t;
    }
};

template <class Backend, class Structure>
class world_frame {
public:
    using tracer_type = tracer<Backend, Structure>;
    explicit world_frame(tracer_type& t) : tracer_(t) {}

    // The ray the passes trace for pixel (x, y): the same floats on every backend.
    static ray pixel_ray(const frame_view& v, int x, int y) {
        std::array<std::uint32_t, VX_WF_HEADER_WORDS> header{};
        write_view(header, v);
        auto r = kernels::scalar::vx_wf_pixel_ray(kernels::scalar::vx_wf_load_view(header.data()), x, y);
        return ray{{r.ox, r.oy, r.oz}, r.tmin, {r.dx, r.dy, r.dz}, r.tmax};
    }

    // Renders `v` through the world the tracer traces, whose words (as last uploaded) are
    // `world` (read for the chunk table's size and the chunk edge only).
    frame_stats render(const frame_view& v, std::span<const std::uint32_t> world) {
        if (world.size() < VX_WD_HEADER_WORDS || world[VX_WD_HEADER_MAGIC] != VX_WD_MAGIC)
            fail("world frame: the words given are not a chunked world's blob");
        if (world[VX_WD_HEADER_CHUNK_BITS] > VX_WF_MAX_CHUNK_BITS)
            fail("world frame: chunks of 2^", world[VX_WD_HEADER_CHUNK_BITS], " voxels a side; the visibility buffer's "
                 "voxel field holds 2^", VX_WF_MAX_CHUNK_BITS, " (24 bits for x, y, z)");
        frame_stats s;
        s.table_rows = world[VX_WD_HEADER_TABLE_ROWS];
        for (;; ++s.restarts) {
            if (s.restarts > 8) fail("world frame: the tile-chunk pair list kept overflowing");
            layout(v, s.table_rows);
            if (run_frame(v, s)) break;
        }
        s.frame_bytes = frame_bytes();
        previous_ = 1 - previous_;
        return s;
    }

    // Per pixel, row-major: the visibility word's low and high halves; the hit's attribute.
    std::vector<std::uint32_t> visibility() { return read_words(header_[VX_WF_HEADER_VISIBILITY_AT], 2 * pixels()); }
    std::vector<std::uint32_t> materials() { return read_words(header_[VX_WF_HEADER_MATERIAL_AT], pixels()); }
    // Visible chunk k's table row (the chunk id of a visibility word is k).
    std::vector<std::uint32_t> visible_rows() {
        auto v = read_words(header_[VX_WF_HEADER_VISIBLE_AT], VX_WF_VISIBLE_WORDS * visible_);
        std::vector<std::uint32_t> rows;
        for (std::size_t k = 0; k < visible_; ++k) rows.push_back(v[k * VX_WF_VISIBLE_WORDS]);
        return rows;
    }

private:
    static void write_float(std::span<std::uint32_t> h, int at, float x) { h[std::size_t(at)] = std::bit_cast<std::uint32_t>(x); }
    static void write_view(std::span<std::uint32_t> h, const frame_view& v) {
        for (int a = 0; a < 3; ++a) {
            write_float(h, VX_WF_HEADER_CAMERA + a, v.position[a]);
            write_float(h, VX_WF_HEADER_FORWARD + a, v.forward[a]);
            write_float(h, VX_WF_HEADER_RIGHT + a, v.right[a]);
            write_float(h, VX_WF_HEADER_UP + a, v.up[a]);
        }
        write_float(h, VX_WF_HEADER_PIXEL_SCALE + 0, 2.0f / float(v.width));
        write_float(h, VX_WF_HEADER_PIXEL_SCALE + 1, 2.0f / float(v.height));
        write_float(h, VX_WF_HEADER_DEPTH_SCALE, float(VX_WF_DEPTH_MAX) / v.far_depth);
        h[VX_WF_HEADER_WIDTH] = std::uint32_t(v.width);
        h[VX_WF_HEADER_HEIGHT] = std::uint32_t(v.height);
        h[VX_WF_HEADER_TILES_X] = std::uint32_t((v.width + 7) >> VX_WF_TILE_BITS);
        h[VX_WF_HEADER_TILES_Y] = std::uint32_t((v.height + 7) >> VX_WF_TILE_BITS);
    }

    std::size_t pixels() const { return std::size_t(header_[VX_WF_HEADER_WIDTH]) * header_[VX_WF_HEADER_HEIGHT]; }
    std::size_t tiles() const { return std::size_t(header_[VX_WF_HEADER_TILES_X]) * header_[VX_WF_HEADER_TILES_Y]; }

    // Lays the sections out for this screen and table (the pair list last); a new layout
    // makes the frame buffer anew, its Hi-Z empty (culling nothing).
    void layout(const frame_view& v, std::uint32_t rows) {
        std::array<std::uint32_t, VX_WF_HEADER_WORDS> h{};
        write_view(h, v);
        std::size_t tile_count = std::size_t(h[VX_WF_HEADER_TILES_X]) * h[VX_WF_HEADER_TILES_Y];
        std::size_t pixel_count = std::size_t(v.width) * std::size_t(v.height);
        pair_capacity_ = std::max<std::size_t>(pair_capacity_, 4 * tile_count);
        std::size_t at = VX_WF_HEADER_WORDS;
        auto section = [&](int word, std::size_t words) {
            h[std::size_t(word)] = std::uint32_t(at);
            at += words;
        };
        section(VX_WF_HEADER_VISIBLE_AT, VX_WF_VISIBLE_WORDS * std::size_t(rows));
        section(VX_WF_HEADER_HIZ_AT, 2 * tile_count);
        at += at & 1;  // 64-bit visibility words
        section(VX_WF_HEADER_VISIBILITY_AT, 2 * pixel_count);
        section(VX_WF_HEADER_MATERIAL_AT, pixel_count);
        section(VX_WF_HEADER_PAIRS_AT, VX_WF_PAIR_WORDS * pair_capacity_);
        if (at > 0xffffffffu) fail("world frame: ", at, " frame words, beyond 32-bit offsets");
        h[VX_WF_HEADER_VISIBLE_CAPACITY] = rows;
        h[VX_WF_HEADER_PAIR_CAPACITY] = std::uint32_t(pair_capacity_);
        bool same = words_ >= at;
        for (int w : {VX_WF_HEADER_VISIBLE_AT, VX_WF_HEADER_HIZ_AT, VX_WF_HEADER_VISIBILITY_AT, VX_WF_HEADER_MATERIAL_AT,
                      VX_WF_HEADER_PAIRS_AT, VX_WF_HEADER_VISIBLE_CAPACITY, VX_WF_HEADER_PAIR_CAPACITY,
                      VX_WF_HEADER_TILES_X, VX_WF_HEADER_TILES_Y})
            same = same && h[std::size_t(w)] == header_[std::size_t(w)];
        header_ = h;
        if (same) return;
        reserve(at);
        words_ = at;
        std::vector<std::uint32_t> empty_hiz(2 * tile_count, 0u);  // key 0: culls nothing
        write_words(header_[VX_WF_HEADER_HIZ_AT], empty_hiz);
        previous_ = 0;
    }

    // One frame's passes; false when a pair list overflowed (it has grown: run again).
    bool run_frame(const frame_view& v, frame_stats& s) {
        write_view(header_, v);
        header_[VX_WF_HEADER_VISIBLE_COUNT] = 0;
        header_[VX_WF_HEADER_PAIR_COUNT] = 0;
        header_[VX_WF_HEADER_HIZ_PREVIOUS] = std::uint32_t(previous_);
        write_words(0, header_);
        std::size_t n_pixels = pixels(), n_tiles = tiles();
        timed(s, frame_stats::clear, VX_WF_PASS_CLEAR, n_pixels);
        timed(s, frame_stats::select_chunks, VX_WF_PASS_SELECT_CHUNKS, s.table_rows);
        s.visible_chunks = std::min(read_word(VX_WF_HEADER_VISIBLE_COUNT), s.table_rows);
        visible_ = s.visible_chunks;
        if (s.visible_chunks > VX_WF_MAX_CHUNKS)
            fail("world frame: ", s.visible_chunks, " chunks in view, more than the visibility buffer's 13-bit chunk "
                 "id holds (", VX_WF_MAX_CHUNKS, "): use larger chunks or a smaller streaming factor");
        auto t0 = std::chrono::steady_clock::now();
        order_nearest_first(s.visible_chunks);
        s.ms[frame_stats::select_chunks] += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        timed(s, frame_stats::select_tiles, VX_WF_PASS_SELECT_TILES, std::uint64_t(s.visible_chunks) * header_[VX_WF_HEADER_TILES_Y]);
        s.pairs = read_word(VX_WF_HEADER_PAIR_COUNT);
        if (grow_pairs(s.pairs)) return false;
        timed(s, frame_stats::march, VX_WF_PASS_MARCH, std::uint64_t(s.pairs) * VX_WF_TILE_PIXELS);
        timed(s, frame_stats::build_hiz, VX_WF_PASS_BUILD_HIZ, n_tiles);
        std::array<std::uint32_t, 1> zero{0};
        write_words(VX_WF_HEADER_PAIR_COUNT, zero);
        timed(s, frame_stats::select_again, VX_WF_PASS_SELECT_TILES_AGAIN, std::uint64_t(s.visible_chunks) * header_[VX_WF_HEADER_TILES_Y]);
        s.pairs_again = read_word(VX_WF_HEADER_PAIR_COUNT);
        if (grow_pairs(s.pairs_again)) return false;
        timed(s, frame_stats::march_again, VX_WF_PASS_MARCH, std::uint64_t(s.pairs_again) * VX_WF_TILE_PIXELS);
        timed(s, frame_stats::build_hiz_again, VX_WF_PASS_BUILD_HIZ, n_tiles);
        timed(s, frame_stats::resolve, VX_WF_PASS_RESOLVE, n_pixels);
        return true;
    }

    // Sorts the visible chunks nearest first (by near key, then table row), so pairs march
    // roughly front to back and the march skips pixels a nearer chunk already covers
    // (world/frame/passes.h); it also makes the chunk ids, which the atomic appends leave in any
    // order, the same on every backend. A few KiB each way, once a frame.
    void order_nearest_first(std::size_t count) {
        if (count < 2) return;
        std::size_t at = header_[VX_WF_HEADER_VISIBLE_AT];
        auto words = read_words(at, VX_WF_VISIBLE_WORDS * count);
        std::vector<std::array<std::uint32_t, VX_WF_VISIBLE_WORDS>> chunks(count);
        for (std::size_t k = 0; k < count; ++k) std::copy_n(&words[k * VX_WF_VISIBLE_WORDS], VX_WF_VISIBLE_WORDS, chunks[k].begin());
        std::sort(chunks.begin(), chunks.end(), [](auto& a, auto& b) {
            return a[3] != b[3] ? a[3] > b[3] : a[0] < b[0];  // words 3 and 0: near key, table row
        });
        for (std::size_t k = 0; k < count; ++k) std::copy_n(chunks[k].begin(), VX_WF_VISIBLE_WORDS, &words[k * VX_WF_VISIBLE_WORDS]);
        write_words(at, words);
    }

    bool grow_pairs(std::uint32_t count) {
        if (count <= pair_capacity_) return false;
        pair_capacity_ = std::size_t(count) * 2;
        return true;
    }

    void timed(frame_stats& s, frame_stats::step step, std::uint32_t pass, std::uint64_t items) {
        auto t0 = std::chrono::steady_clock::now();
        run(pass, items);
        s.ms[step] += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    }

    std::uint32_t read_word(int at) { return read_words(std::size_t(at), 1)[0]; }

    // The backend side: the GPU engines' frame buffer and pass entry, or host words and
    // the CPU engine's workers running the scalar pass function.
    static constexpr bool on_device = pass_engine<typename tracer_type::engine_type>;

    void reserve(std::size_t words) {
        if constexpr (on_device) tracer_.engine().frame_reserve(words);
        else host_.assign(words, 0u);
    }
    void write_words(std::size_t at, std::span<const std::uint32_t> w) {
        if constexpr (on_device) tracer_.engine().frame_write(at, w);
        else std::copy(w.begin(), w.end(), host_words() + at);
    }
    std::vector<std::uint32_t> read_words(std::size_t at, std::size_t n) {
        std::vector<std::uint32_t> w(n);
        if constexpr (on_device) tracer_.engine().frame_read(at, w);
        else std::copy_n(host_words() + at, n, w.begin());
        return w;
    }
    void run(std::uint32_t pass, std::uint64_t items) {
        if constexpr (on_device) {
            tracer_.engine().run_pass(pass, items);
        } else {
            const std::uint32_t* blob = tracer_.engine().blob_view().data();
            std::uint32_t* frame = host_words();
            constexpr std::uint64_t batch = 256;
            tracer_.engine().pool()->parallel_for(std::size_t((items + batch - 1) / batch), [&](std::size_t b) {
                std::uint64_t end = std::min<std::uint64_t>(items, (b + 1) * batch);
                for (std::uint64_t i = b * batch; i < end; ++i) kernels::scalar::vx_world_pass(blob, frame, pass, std::uint32_t(i));
            });
        }
    }
    std::uint64_t frame_bytes() const {
        if constexpr (on_device) return tracer_.engine().frame_bytes();
        else return host_.size() * sizeof(std::uint32_t);
    }
    std::uint32_t* host_words() { return host_.data(); }

    tracer_type& tracer_;
    std::array<std::uint32_t, VX_WF_HEADER_WORDS> header_{};
    std::size_t words_ = 0, pair_capacity_ = 0, visible_ = 0;
    int previous_ = 0;
    // The CPU's frame words; operator new aligns them for the 64-bit atomics.
    static_assert(__STDCPP_DEFAULT_NEW_ALIGNMENT__ >= 8);
    std::vector<std::uint32_t> host_;
};

}  // namespace voxray
