// Built-in procedural scenes by name, for tools, benchmarks and tests:
//
//   spec := NAME [":" SIZE] {":" KEY "=" VALUE}
//
//   terrain[:SIZE][:seed=N][:skin=N]   SIZE = footprint edge, 64..8192 (default 1024)
//                                      seed = any unsigned 64-bit number (default 1)
//                                      skin = voxels under each column top, 1..64 (default 4)
//   sphere30, checker, noise50, terrain64
//                                      one 64^3 chunk each, for the mesher (chunk_scenes.hpp)
//   menger[:SIZE]                      SIZE = cell * 3^level, level 1..7, cell 1..8 and not a
//                                      multiple of 3: the edge in voxels (default 486 =
//                                      level 5 with 2-voxel cells; 729 = level 6, 64 M voxels)
//
// Examples: "terrain", "terrain:2048", "terrain:1024:seed=7", "menger:243", "menger:729".
// Defaults (2 threads, see the project notes for timings): terrain ~1024^2 footprint,
// menger 486^3 with 25.6 M voxels.
#pragma once
#include <charconv>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/scenes/chunk_scenes.hpp"
#include "voxray/scenes/menger.hpp"
#include "voxray/scenes/terrain.hpp"

namespace voxray::scenes {

inline const std::vector<std::string_view>& builtin_names() {
    static const std::vector<std::string_view> names{"terrain", "menger", "sphere30", "checker", "noise50", "terrain64"};
    return names;
}

namespace builtin_detail {

struct parsed_spec {
    std::string_view name;
    std::string_view size;  // empty: default
    std::vector<std::pair<std::string_view, std::string_view>> options;
};

inline parsed_spec parse(std::string_view spec) {
    parsed_spec p;
    std::size_t start = 0;
    for (int part = 0;; ++part) {
        auto end = spec.find(':', start);
        auto piece = spec.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
        if (part == 0) {
            p.name = piece;
        } else if (auto eq = piece.find('='); eq != std::string_view::npos) {
            p.options.emplace_back(piece.substr(0, eq), piece.substr(eq + 1));
        } else if (part == 1) {
            p.size = piece;
            if (piece.empty()) fail("scene spec '", spec, "': empty size");
        } else {
            fail("scene spec '", spec, "': unexpected '", piece, "' (options are KEY=VALUE)");
        }
        if (end == std::string_view::npos) break;
        start = end + 1;
    }
    return p;
}

template <class T>
T number(std::string_view spec, std::string_view what, std::string_view text) {
    T value{};
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
    if (ec != std::errc() || ptr != text.data() + text.size() || text.empty())
        fail("scene spec '", spec, "': ", what, " '", text, "' is not a valid number");
    return value;
}

}  // namespace builtin_detail

// Builds the scene named by `spec` (syntax above). `threads`: 0 = all hardware threads.
inline voxel_model make_builtin(std::string_view spec, unsigned threads = 0) {
    using namespace builtin_detail;
    auto p = parse(spec);
    auto unknown_option = [&](std::string_view key, const char* valid) {
        fail("scene spec '", spec, "': '", p.name, "' has no option '", key, "' (valid: ", valid, ")");
    };
    if (p.name == "terrain") {
        terrain_options opt;
        opt.threads = threads;
        if (!p.size.empty()) opt.size = number<int>(spec, "size", p.size);
        for (auto [key, value] : p.options) {
            if (key == "seed") opt.seed = number<std::uint64_t>(spec, "seed", value);
            else if (key == "skin") opt.skin = number<int>(spec, "skin", value);
            else unknown_option(key, "seed, skin");
        }
        return make_terrain(opt);
    }
    if (p.name == "menger") {
        menger_options opt;
        opt.threads = threads;
        if (!p.size.empty()) {
            auto size = number<int>(spec, "size", p.size);
            int level = 0, cell = size;
            while (cell > 0 && cell % 3 == 0) cell /= 3, ++level;
            if (size < 3 || level < 1 || level > 7 || cell > 8)
                fail("scene spec '", spec, "': menger size ", size,
                     " is not cell * 3^level with level 1..7 and cell 1..8 (e.g. 243, 486, 729)");
            opt.level = level, opt.cell = cell;
        }
        for (auto [key, value] : p.options) unknown_option(key, "none");
        return make_menger(opt);
    }
    if (is_chunk_scene(p.name)) {
        if (!p.size.empty() || !p.options.empty()) fail("scene spec '", spec, "': '", p.name, "' takes no size or options");
        return make_chunk_scene(p.name);
    }
    std::string names;
    for (auto n : builtin_names()) names += (names.empty() ? "" : ", ") + std::string(n);
    fail("unknown built-in scene '", p.name, "' in spec '", spec, "' (available: ", names, ")");
}

}  // namespace voxray::scenes
