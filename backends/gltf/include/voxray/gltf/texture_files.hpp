// The texture files an OBJ's materials name (io/mtl_reader.hpp), decoded with stb_image to
// RGBA8. A diffuse texture with an alpha channel that is not all opaque makes its material
// cut out where alpha < 0.5 (MTL has no alpha mode; this is what exporters of leaf cards
// mean). A missing or undecodable file is an error naming it and the reason.
#pragma once
#include <cstring>
#include <filesystem>
#include <string>

#include <stb/stb_image.h>

#include "voxray/core/error.hpp"
#include "voxray/io/mesh_surface.hpp"

namespace voxray::gltf {

inline void decode_texture(io::mesh_texture& t) {
    if (t.decoded()) return;
    if (!std::filesystem::exists(t.path)) fail("texture file ", t.path, " does not exist");
    int w = 0, h = 0, channels = 0;
    unsigned char* pixels = stbi_load(t.path.c_str(), &w, &h, &channels, 4);
    if (!pixels) fail("texture file ", t.path, ": cannot be decoded (", stbi_failure_reason(), ")");
    t.width = w, t.height = h;
    t.rgba.assign(pixels, pixels + std::size_t(w) * std::size_t(h) * 4);
    stbi_image_free(pixels);
}

inline void decode_textures(io::mesh_surface& s) {
    for (io::mesh_texture& t : s.textures) decode_texture(t);
    for (io::mesh_material& m : s.materials) {
        if (m.texture < 0 || m.alpha != io::alpha_mode::opaque) continue;
        const io::mesh_texture& t = s.textures[std::size_t(m.texture)];
        for (std::size_t i = 3; i < t.rgba.size(); i += 4)
            if (t.rgba[i] < 255) {
                m.alpha = io::alpha_mode::mask;
                break;
            }
    }
}

}  // namespace voxray::gltf
