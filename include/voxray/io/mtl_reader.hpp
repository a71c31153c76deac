// Wavefront MTL reader, for OBJ meshes with colour (io/obj_reader.hpp, obj_options::materials):
// per material its diffuse colour (Kd), dissolve (d, or Tr = 1 - d), diffuse texture
// (map_Kd) and coverage texture (map_d). Texture files are named, not decoded: decoding needs
// an image library, which the header-only core does not take (voxray/gltf/coloured_mesh.hpp
// decodes them). Kd is read as a display (sRGB) colour and stored linear (io/mesh_surface.hpp).
// A material with a coverage texture, or whose diffuse texture has an alpha channel, is cut
// out where alpha < 0.5; a constant d below 1 (glass) keeps its voxels.
// Every error names the file, the line and the offending text.
#pragma once
#include <filesystem>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/io/mesh_surface.hpp"
#include "voxray/io/mesh_text.hpp"

namespace voxray::io {

// Adds the materials of MTL text `text` (from file `name`, textures relative to `folder`) to
// `surface`; `index` maps material names to their index in surface.materials.
inline void parse_mtl(std::string_view text, const std::string& name, const std::filesystem::path& folder,
                      mesh_surface& surface, std::unordered_map<std::string, std::uint32_t>& index) {
    using namespace detail;
    std::unordered_map<std::string, int> texture_index;
    for (std::size_t i = 0; i < surface.textures.size(); ++i) texture_index[surface.textures[i].path] = int(i);
    mesh_material* current = nullptr;
    line_cursor lines(text);
    std::string_view line;
    while (lines.next(line)) {
        auto at = [&] { return name + ":" + std::to_string(lines.line_number()); };
        std::string_view rest = line;
        auto key = next_token(rest);
        if (key == "newmtl") {
            std::string mname(trimmed(rest));
            if (mname.empty()) fail(at(), ": newmtl without a name");
            auto [it, fresh] = index.emplace(mname, std::uint32_t(surface.materials.size()));
            if (fresh) surface.materials.emplace_back().name = mname;
            current = &surface.materials[it->second];
            continue;
        }
        if (key.empty() || key[0] == '#') continue;
        if (!current) {
            if (key == "Kd" || key == "d" || key == "Tr" || key == "map_Kd" || key == "map_d")
                fail(at(), ": ", quote(key), " before any newmtl");
            continue;
        }
        auto numbers = [&](int n, double* out) {
            for (int k = 0; k < n; ++k) {
                auto tok = next_token(rest);
                if (!parse_number(tok, out[k]) || !std::isfinite(out[k]))
                    fail(at(), ": bad ", quote(key), " value ", quote(tok));
            }
        };
        if (key == "Kd") {
            double c[3];
            numbers(3, c);
            for (int k = 0; k < 3; ++k) current->base_colour[k] = srgb_to_linear(float(std::clamp(c[k], 0.0, 1.0)));
        } else if (key == "d" || key == "Tr") {
            double d;
            numbers(1, &d);
            current->base_colour.a = float(std::clamp(key == "d" ? d : 1.0 - d, 0.0, 1.0));
        } else if (key == "map_Kd" || key == "map_d") {
            // Options (-s 1 1 1, -clamp on, ...) come first; the file name is the last token.
            std::string_view file;
            for (auto tok = next_token(rest); !tok.empty(); tok = next_token(rest)) file = tok;
            if (file.empty()) fail(at(), ": ", quote(key), " without a file");
            std::string path = (folder / std::filesystem::path(std::string(file))).lexically_normal().string();
            auto [it, fresh] = texture_index.emplace(path, int(surface.textures.size()));
            if (fresh) surface.textures.emplace_back().path = path;
            (key == "map_Kd" ? current->texture : current->alpha_texture) = it->second;
            if (key == "map_d") current->alpha = alpha_mode::mask;
        }
        // Anything else (Ka, Ks, Ns, illum, bump, ...) does not change the colour a voxel takes.
    }
}

inline void read_mtl(const std::filesystem::path& path, mesh_surface& surface,
                     std::unordered_map<std::string, std::uint32_t>& index) {
    auto text = detail::read_whole_file(path);
    parse_mtl(text, path.string(), path.parent_path(), surface, index);
}

}  // namespace voxray::io
