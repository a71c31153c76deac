// What a mesh's surface looks like: materials (a base colour, a base-colour texture, an
// alpha rule), per-corner texture coordinates and colours, one material per triangle. The
// coloured readers fill it (OBJ with MTL: io/obj_reader.hpp and io/mtl_reader.hpp; glTF:
// voxray/gltf/gltf_reader.hpp), and the voxelizer colours each voxel by what it covers.
//
// Colour spaces follow glTF: factors and corner colours are linear, texels are sRGB-encoded
// (decoded to linear before they are multiplied), colour_at() answers in linear RGB.
// Texture coordinates: (0, 0) is the image's top-left texel's corner, v grows downwards
// (glTF's convention; the OBJ reader flips v on the way in).
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "voxray/core/error.hpp"

namespace voxray::io {

enum class texture_wrap { repeat, clamp, mirror };

struct mesh_texture {
    std::string path;                  // the file (or "image N of FILE"), for messages
    int width = 0, height = 0;
    std::vector<std::uint8_t> rgba;    // width * height * 4, rows top to bottom; empty: not decoded yet
    texture_wrap wrap_u = texture_wrap::repeat, wrap_v = texture_wrap::repeat;

    bool decoded() const { return !rgba.empty(); }
};

// opaque: alpha is ignored. mask: the surface is there where alpha >= alpha_cutoff.
// blend: fractional coverage; a voxelizer keeps it where alpha >= 0.5.
enum class alpha_mode { opaque, mask, blend };

struct mesh_material {
    std::string name;
    glm::vec4 base_colour{1.0f};  // linear RGBA
    int texture = -1;             // base-colour texture (multiplies base_colour), or -1
    int alpha_texture = -1;       // a separate coverage texture (OBJ map_d: its first channel), or -1
    alpha_mode alpha = alpha_mode::opaque;
    float alpha_cutoff = 0.5f;
    bool double_sided = false;    // seen from behind too (glTF doubleSided: leaf cards)

    // Whether the alpha test can drop parts of this material's triangles.
    bool cuts() const { return alpha != alpha_mode::opaque; }
    float cutoff() const { return alpha == alpha_mode::mask ? alpha_cutoff : 0.5f; }
};

inline float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }
inline float linear_to_srgb(float c) {
    c = std::clamp(c, 0.0f, 1.0f);
    return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
}

struct mesh_surface {
    std::vector<mesh_material> materials;
    std::vector<mesh_texture> textures;
    std::vector<std::uint32_t> triangle_materials;  // one per triangle; empty: the mesh has no colour
    std::vector<glm::vec2> corner_uvs;              // 3 per triangle, or empty
    std::vector<glm::vec4> corner_colours;          // 3 per triangle (linear RGBA), or empty

    bool coloured() const { return !triangle_materials.empty(); }

    // Throws, naming what is wrong, unless the arrays fit `triangles` triangles, every index is
    // in range, every number finite and every texture a material uses decoded.
    void validate(std::size_t triangles) const {
        if (!coloured()) return;
        if (triangle_materials.size() != triangles)
            fail("mesh surface has ", triangle_materials.size(), " triangle materials for ", triangles, " triangles");
        if (!corner_uvs.empty() && corner_uvs.size() != 3 * triangles)
            fail("mesh surface has ", corner_uvs.size(), " texture coordinates for ", triangles, " triangles (3 each)");
        if (!corner_colours.empty() && corner_colours.size() != 3 * triangles)
            fail("mesh surface has ", corner_colours.size(), " corner colours for ", triangles, " triangles (3 each)");
        for (std::size_t t = 0; t < triangles; ++t)
            if (triangle_materials[t] >= materials.size())
                fail("mesh triangle ", t, " uses material ", triangle_materials[t], " of ", materials.size());
        for (std::size_t i = 0; i < corner_uvs.size(); ++i)
            if (!std::isfinite(corner_uvs[i].x) || !std::isfinite(corner_uvs[i].y))
                fail("mesh triangle ", i / 3, " corner ", i % 3, " has a non-finite texture coordinate");
        for (std::size_t i = 0; i < corner_colours.size(); ++i)
            for (int k = 0; k < 4; ++k)
                if (!std::isfinite(corner_colours[i][k]))
                    fail("mesh triangle ", i / 3, " corner ", i % 3, " has a non-finite colour");
        for (const auto& m : materials)
            for (int t : {m.texture, m.alpha_texture}) {
                if (t < 0) continue;
                if (std::size_t(t) >= textures.size())
                    fail("material '", m.name, "' uses texture ", t, " of ", textures.size());
                const mesh_texture& tex = textures[std::size_t(t)];
                if (!tex.decoded())
                    fail("material '", m.name, "' uses texture ", tex.path, ", which was not decoded ",
                         "(load coloured meshes with voxray/gltf/coloured_mesh.hpp, target voxray::gltf)");
                if (tex.rgba.size() != std::size_t(tex.width) * std::size_t(tex.height) * 4)
                    fail("texture ", tex.path, " holds ", tex.rgba.size(), " bytes for ", tex.width, " x ", tex.height,
                         " RGBA texels");
            }
    }

    // Whether the colour varies over triangle t (a texture or corner colours).
    bool varies(std::size_t t) const {
        const mesh_material& m = materials[triangle_materials[t]];
        return m.texture >= 0 || m.alpha_texture >= 0 || !corner_colours.empty();
    }

    // The linear RGBA of triangle t at barycentric coordinates `b` (weights of its 3 corners).
    glm::vec4 colour_at(std::size_t t, glm::dvec3 b) const { return surface_at(t, b, true); }

    // Its alpha alone (what the alpha rule reads), without decoding a texel's colour.
    float alpha_at(std::size_t t, glm::dvec3 b) const { return surface_at(t, b, false).a; }

    // Bilinear sample of `tex` at `uv` (channels 0..1, as stored: sRGB for colour textures).
    static glm::vec4 sample(const mesh_texture& tex, glm::vec2 uv) {
        uv = glm::clamp(uv, glm::vec2(-1e5f), glm::vec2(1e5f));  // texel indices stay far inside int
        float x = uv.x * float(tex.width) - 0.5f, y = uv.y * float(tex.height) - 0.5f;
        float fx = std::floor(x), fy = std::floor(y);
        int x0 = int(fx), y0 = int(fy);
        float ax = x - fx, ay = y - fy;
        glm::vec4 out(0.0f);
        for (int dy = 0; dy < 2; ++dy)
            for (int dx = 0; dx < 2; ++dx) {
                int tx = wrapped(x0 + dx, tex.width, tex.wrap_u), ty = wrapped(y0 + dy, tex.height, tex.wrap_v);
                std::size_t texel = std::size_t(ty) * std::size_t(tex.width) + std::size_t(tx);
                const std::uint8_t* p = tex.rgba.data() + texel * 4;
                float w = (dx ? ax : 1.0f - ax) * (dy ? ay : 1.0f - ay);
                out += w * glm::vec4(p[0], p[1], p[2], p[3]) / 255.0f;
            }
        return out;
    }

private:
    // colour_at, or (rgb false) its alpha with the colour channels left undecoded (1).
    glm::vec4 surface_at(std::size_t t, glm::dvec3 b, bool rgb) const {
        const mesh_material& m = materials[triangle_materials[t]];
        glm::vec4 c = m.base_colour;
        if (!corner_colours.empty())
            c *= corner_colours[3 * t] * float(b.x) + corner_colours[3 * t + 1] * float(b.y) +
                 corner_colours[3 * t + 2] * float(b.z);
        if ((m.texture >= 0 || m.alpha_texture >= 0) && !corner_uvs.empty()) {
            glm::vec2 uv = corner_uvs[3 * t] * float(b.x) + corner_uvs[3 * t + 1] * float(b.y) +
                           corner_uvs[3 * t + 2] * float(b.z);
            if (m.texture >= 0) {
                glm::vec4 texel = sample(textures[std::size_t(m.texture)], uv);
                c *= rgb ? glm::vec4(srgb_to_linear(texel.r), srgb_to_linear(texel.g), srgb_to_linear(texel.b), texel.a)
                         : glm::vec4(1.0f, 1.0f, 1.0f, texel.a);
            }
            if (m.alpha_texture >= 0) c.a *= sample(textures[std::size_t(m.alpha_texture)], uv).r;
        }
        return c;
    }

    static int wrapped(int i, int n, texture_wrap mode) {
        if (unsigned(i) < unsigned(n)) return i;  // inside: every mode leaves it (and skips the divisions)
        if (mode == texture_wrap::clamp) return std::clamp(i, 0, n - 1);
        int period = mode == texture_wrap::mirror ? 2 * n : n;
        int k = ((i % period) + period) % period;
        return mode == texture_wrap::mirror && k >= n ? period - 1 - k : k;
    }
};

}  // namespace voxray::io
