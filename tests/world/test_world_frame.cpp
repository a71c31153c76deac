// The GPU-driven passes (world/frame/passes.h) on every backend: per pixel, the visibility word
// and the resolved attribute must be what the world's own trace finds for the same ray
// (same voxel of the same chunk, face, depth key and attribute), frame after frame, with
// the previous frame's Hi-Z culling tiles, a camera inside a chunk (the self chunk) and a
// jump that makes the previous Hi-Z wrong (the second tile pass must mend it).
#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "voxray/cpu.hpp"
#include "voxray/tracer.hpp"
#include "voxray/world/frame/frame.hpp"
#include "every_backend.hpp"
#include "world_test_model.hpp"

namespace voxray {
namespace {

using namespace voxray::test;

constexpr int width = 96, height = 72;
constexpr float far_depth = 4000.0f;

// Colour blocks (so the resolve's colour-block search is checked), 16^3 chunks, a cut
// with coarse chunks split around finer ones.
chunked_world frame_world() {
    voxel_model model = world_test_model();
    for (int i = 1; i < 256; ++i)
        model.palette()[std::uint8_t(i)].colour = rgba{std::uint8_t(i), std::uint8_t(255 - i), std::uint8_t(i / 2), 255};
    world_options o;
    o.chunk_bits = 4;
    o.threads = 2;
    o.attributes = svdag_attributes::colour_blocks;
    chunked_world w(model, o);
    w.show(split_cut(w));
    return w;
}

frame_view view_of(glm::vec3 eye, glm::vec3 target) { return frame_view(look_at(eye, target, 60.0f), width, height, far_depth); }

// Compares one rendered frame with the trace of its rays; returns the pixels with a hit.
template <class Backend>
std::size_t frame_matches_the_trace(const chunked_world& w, tracer<Backend, chunked_world>& t,
                                    world_frame<Backend, chunked_world>& frame, const frame_view& v, const char* what) {
    SCOPED_TRACE(what);
    std::vector<ray> rays;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) rays.push_back(world_frame<Backend, chunked_world>::pixel_ray(v, x, y));
    std::vector<hit> hits(rays.size());
    t.closest_hit(rays, hits);
    auto vis = frame.visibility();
    auto materials = frame.materials();
    auto rows = frame.visible_rows();
    std::span<const std::uint32_t> blob = w.blob();
    auto header_ivec3 = [&](int at) { return glm::ivec3{int(blob[at]), int(blob[at + 1]), int(blob[at + 2])}; };
    glm::ivec3 origin = header_ivec3(VX_WD_HEADER_ORIGIN), shift = header_ivec3(VX_WD_HEADER_SHIFT);
    int edge_mask = (1 << int(blob[VX_WD_HEADER_CHUNK_BITS])) - 1;
    float scale = float(VX_WF_DEPTH_MAX) / far_depth;
    std::size_t hit_pixels = 0, mismatches = 0;
    for (std::size_t i = 0; i < rays.size(); ++i) {
        std::uint32_t lo = vis[2 * i], hi = vis[2 * i + 1];
        const hit& h = hits[i];
        std::string problem;
        if (!h.is_hit()) {
            if (lo | hi) problem = "a visibility word where the trace misses";
        } else if (!(lo | hi)) {
            problem = "no visibility word where the trace hits";
        } else {
            ++hit_pixels;
            std::uint32_t k = VX_WF_CHUNK(hi, lo);
            if (k >= rows.size()) {
                problem = "chunk id " + std::to_string(k) + " of " + std::to_string(rows.size()) + " visible";
            } else {
                std::uint32_t row = blob[VX_WD_HEADER_TABLE] + rows[k] * VX_WD_ROW_WORDS;
                int lod = int(blob[row + VX_WD_ROW_LOD]);
                glm::ivec3 walk = h.voxel - origin, grid = walk + shift;
                bool inside = true;
                for (int a = 0; a < 3; ++a)
                    inside = inside && walk[a] >= int(blob[row + VX_WD_ROW_MIN + a]) && walk[a] < int(blob[row + VX_WD_ROW_MAX + a]);
                glm::ivec3 local = (grid >> lod) & edge_mask;
                if (!inside) problem = "the hit voxel is outside the chunk named";
                else if (local != glm::ivec3(int(VX_WF_X(lo)), int(VX_WF_Y(lo)), int(VX_WF_Z(lo)))) problem = "another voxel";
                else if (VX_WF_FACE(hi) != std::uint32_t(h.normal)) problem = "another face";
                else if (VX_WF_DEPTH(hi) != kernels::scalar::vx_wf_depth_key(h.t, scale)) problem = "another depth";
                else if (materials[i] != h.material) problem = "another attribute";
            }
        }
        if (!problem.empty() && mismatches++ < 3)
            ADD_FAILURE() << "pixel " << i % width << " " << i / width << ": " << problem << " (trace: hit " << h.is_hit()
                          << " voxel " << h.voxel.x << " " << h.voxel.y << " " << h.voxel.z << " t " << h.t << ")";
    }
    EXPECT_EQ(mismatches, 0u);
    return hit_pixels;
}

template <class Backend>
void frames_match_the_trace(const char* backend) {
    chunked_world w = frame_world();
    tracer<Backend, chunked_world> t(w);
    world_frame<Backend, chunked_world> frame(t);
    // The terrain is Z up, 120 voxels a side; the noise block hangs off its low x side.
    glm::vec3 lo(w.bounds().min), hi(w.bounds().max), centre = (lo + hi) * 0.5f;
    auto above = [&](float height) { return glm::vec3(60.0f, 60.0f, hi.z + height); };
    glm::vec3 below(61.0f, 60.0f, lo.z);
    struct step {
        const char* what;
        frame_view view;
        int lod;  // the cut shown: -1 the split cut, else every chunk of that LOD
    };
    step path[] = {
        {"split cut, from afar", view_of(centre + glm::vec3(130, 120, 60), centre), -1},
        {"split cut, inside a chunk", view_of(glm::vec3(30.0f, 60.0f, lo.z + 0.6f * (hi.z - lo.z)), glm::vec3(hi.x, hi.y, lo.z)), -1},
        {"LOD 0, looking down", view_of(above(30.0f), below), 0},
        {"LOD 0, the same view again", view_of(above(30.0f), below), 0},
        {"LOD 0, a jump up", view_of(above(90.0f), below), 0},
        {"LOD 1, from afar", view_of(centre + glm::vec3(-130, 120, 60), centre), 1},
    };
    std::vector<frame_stats> stats;
    int shown = -1;
    for (auto& s : path) {
        if (s.lod != shown) {
            if (s.lod >= 0) w.show_lod(s.lod);
            t.update(w);
            shown = s.lod;
        }
        stats.push_back(frame.render(s.view, w.blob()));
        std::string what = std::string(backend) + ", " + s.what;
        std::size_t hit_pixels = frame_matches_the_trace<Backend>(w, t, frame, s.view, what.c_str());
        const frame_stats& f = stats.back();
        EXPECT_GT(hit_pixels, std::size_t(width * height / 8)) << what;
        EXPECT_GT(f.visible_chunks, 0u) << what;
        EXPECT_LE(f.visible_chunks, f.table_rows) << what;
        std::printf("[%s] %zu hit pixels; %u of %u chunks visible, %u + %u tile-chunk pairs, %.2f ms\n", what.c_str(),
                    hit_pixels, f.visible_chunks, f.table_rows, f.pairs, f.pairs_again, f.total_ms());
    }
    // The previous frame's Hi-Z culls occluded tiles: the same view again marches fewer
    // pairs, and, as the culled chunks are behind every pixel of their tiles, none of
    // them comes back in the second tile pass.
    EXPECT_LT(stats[3].pairs, stats[2].pairs);
    EXPECT_EQ(stats[3].pairs_again, 0u);
    // After the jump up every surface is farther than the previous Hi-Z says: the first
    // tile pass culls chunks that are in view, and the second must add them back.
    EXPECT_GT(stats[4].pairs_again, 0u);
}

template <class Backend>
struct world_frame_on : ::testing::Test {};
TYPED_TEST_SUITE(world_frame_on, every_backend, backend_names);

TYPED_TEST(world_frame_on, frames_match_the_trace) { frames_match_the_trace<TypeParam>(TypeParam::name); }

TEST(world_frame, chunks_wider_than_the_visibility_word_are_refused) {
    voxel_model model = scenes::make_builtin("terrain:64", 2);
    world_options o;
    o.chunk_bits = 9;
    chunked_world w(model, o);
    tracer<cpu, chunked_world> t(w);
    world_frame<cpu, chunked_world> frame(t);
    try {
        frame.render(view_of({-50, 80, -50}, {32, 10, 32}), w.blob());
        ADD_FAILURE() << "a world of 2^9 chunks rendered";
    } catch (const error& e) {
        EXPECT_NE(std::string(e.what()).find("2^9"), std::string::npos) << e.what();
    }
    EXPECT_THROW(frame_view(look_at({0, 0, 0}, {1, 0, 0}), 0, 10, 100.0f), error);
}

}  // namespace
}  // namespace voxray
