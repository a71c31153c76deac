// world-fly --appearance SET: each frame's LOD cut walked with the world's appearance tables
// of SET (world-build MESH --appearance SET; appearance/world/chunk_tables.hpp), front to back
// through the filtered voxels, beside the traced frame. The cut is the LOD selection at the
// flight's StreamingFactor (world/lod_select.hpp, no byte budget); chunk walkers are read
// once and kept while they stay in the cut. The walk runs on the CPU whatever --backend is.
#pragma once
#include <chrono>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "voxray/appearance/world/chunk_tables.hpp"
#include "voxray/core/error.hpp"
#include "voxray/io/surface_sample.hpp"
#include "voxray/rays/shading.hpp"
#include "voxray/world/lod_select.hpp"

namespace voxray::tool {

class fly_appearance {
public:
    // Fails, naming the folder, when the world has no tables of `set`.
    fly_appearance(const std::filesystem::path& dir, const world_manifest& m, std::string set, unsigned threads)
        : dir_(dir), manifest_(m), set_(std::move(set)), threads_(threads), tree_(m) {
        appearance::check_set_name(set_);
        const auto folder = dir / "appearance" / set_;
        if (!std::filesystem::is_directory(folder))
            fail("--appearance: ", folder.string(), " does not exist (world-build MESH --appearance ", set_,
                 " makes a world's tables)");
    }

    struct frame {
        std::vector<std::uint8_t> rgb;  // sRGB, 3 bytes a pixel, the sky where the walk saw through
        std::size_t chunks = 0, read = 0;
        double read_ms = 0, walk_ms = 0, visits = 0;  // visits: voxels blended a ray, on average
    };

    // The frame of `rays` (one a pixel) seen from `eye`, the cut at `factor`, lit by `sun`.
    frame walk(const std::vector<ray>& rays, glm::dvec3 eye, double factor, glm::vec3 sun, int up_axis) {
        frame out;
        auto start = std::chrono::steady_clock::now();
        appearance::placed_walker<appearance::chunk_walker> cut;
        std::map<chunk_key, std::shared_ptr<const appearance::chunk_walker>, chunk_key_less> kept;
        for (const lod_choice& c : tree_.select(eye, factor)) {
            auto found = walkers_.find(c.key);
            auto w = found != walkers_.end() ? found->second
                                             : appearance::chunk_walker_of(dir_, manifest_, set_, c.key);
            out.read += found == walkers_.end();
            cut.add(appearance::chunk_placement(manifest_.grid, c.key), w);
            kept.emplace(c.key, std::move(w));
        }
        walkers_ = std::move(kept);  // chunks that left the cut are let go
        out.chunks = walkers_.size();
        auto walked = std::chrono::steady_clock::now();
        const appearance_light light{.to_light = sun, .ambient = 0.2f, .shadows = false};
        std::vector<appearance_pixel> px = cut.walk(rays, light, threads_);
        auto done = std::chrono::steady_clock::now();
        out.read_ms = std::chrono::duration<double, std::milli>(walked - start).count();
        out.walk_ms = std::chrono::duration<double, std::milli>(done - walked).count();
        out.rgb.reserve(px.size() * 3);
        for (std::size_t i = 0; i < px.size(); ++i) {
            glm::vec3 c = glm::vec3(px[i].r, px[i].g, px[i].b) + px[i].transmittance * sky(rays[i].direction, up_axis);
            rgba e = io::encode_srgb8(glm::vec4(glm::clamp(c, 0.0f, 1.0f), 1.0f));
            out.rgb.insert(out.rgb.end(), {e.r, e.g, e.b});
            out.visits += px[i].visits;
        }
        out.visits /= px.empty() ? 1.0 : double(px.size());
        return out;
    }

private:
    std::filesystem::path dir_;
    const world_manifest& manifest_;
    std::string set_;
    unsigned threads_;
    lod_tree tree_;
    std::map<chunk_key, std::shared_ptr<const appearance::chunk_walker>, chunk_key_less> walkers_;
};

}  // namespace voxray::tool
