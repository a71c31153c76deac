// glTF 2.0 (.gltf with its .bin and images, or .glb) as a coloured triangle mesh, through
// TinyGLTF: the default scene's node tree with every node's transform applied (matrix, or
// translation x rotation x scale), triangles, strips and fans (points and lines carry no
// surface), and per material its base colour factor, base-colour texture (with its sampler's
// wrap modes and its TEXCOORD set), COLOR_0 and the alpha mode and cutoff
// (io/mesh_surface.hpp). A primitive without a material is white, as the spec says.
// Errors name the file and what is wrong (the accessor, the image, the limit).
#pragma once
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include <glm/ext/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/mat4x4.hpp>
#include <tiny_gltf.h>

#include "voxray/core/error.hpp"
#include "voxray/io/mesh.hpp"

namespace voxray::gltf {

namespace detail {

// Accessor `index` of `m` as `count x n` floats (n = its components, at most `most`):
// floats as they are, normalized integers scaled to 0..1 (or -1..1), other integers as
// their values.
inline std::vector<float> read_floats(const tinygltf::Model& m, int index, int& n, const std::string& file) {
    if (index < 0 || std::size_t(index) >= m.accessors.size())
        fail(file, ": accessor ", index, " does not exist (the file has ", m.accessors.size(), ")");
    const tinygltf::Accessor& a = m.accessors[std::size_t(index)];
    if (a.sparse.isSparse) fail(file, ": accessor ", index, " is sparse, which voxray does not read");
    n = tinygltf::GetNumComponentsInType(std::uint32_t(a.type));
    int size = tinygltf::GetComponentSizeInBytes(std::uint32_t(a.componentType));
    if (n <= 0 || size <= 0) fail(file, ": accessor ", index, " has an unknown type or component type");
    std::vector<float> out(a.count * std::size_t(n), 0.0f);
    if (a.bufferView < 0) return out;  // all zeros, as the spec says
    if (std::size_t(a.bufferView) >= m.bufferViews.size())
        fail(file, ": accessor ", index, " uses buffer view ", a.bufferView, " of ", m.bufferViews.size());
    const tinygltf::BufferView& v = m.bufferViews[std::size_t(a.bufferView)];
    if (v.buffer < 0 || std::size_t(v.buffer) >= m.buffers.size())
        fail(file, ": buffer view ", a.bufferView, " uses buffer ", v.buffer, " of ", m.buffers.size());
    const std::vector<unsigned char>& bytes = m.buffers[std::size_t(v.buffer)].data;
    std::size_t element = std::size_t(n) * std::size_t(size);
    std::size_t stride = v.byteStride ? v.byteStride : element;
    std::size_t first = v.byteOffset + a.byteOffset;
    if (a.count > 0 && (first + (a.count - 1) * stride + element > v.byteOffset + v.byteLength ||
                        v.byteOffset + v.byteLength > bytes.size()))
        fail(file, ": accessor ", index, " (", a.count, " elements of ", element, " bytes, stride ", stride,
             ") reaches past its buffer view or buffer (", bytes.size(), " bytes)");
    for (std::size_t i = 0; i < a.count; ++i)
        for (int k = 0; k < n; ++k) {
            const unsigned char* p = bytes.data() + first + i * stride + std::size_t(k) * std::size_t(size);
            float value = 0;
            switch (a.componentType) {
                case TINYGLTF_COMPONENT_TYPE_FLOAT: std::memcpy(&value, p, 4); break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: value = float(*p) / (a.normalized ? 255.0f : 1.0f); break;
                case TINYGLTF_COMPONENT_TYPE_BYTE:
                    value = std::max(float(std::int8_t(*p)) / (a.normalized ? 127.0f : 1.0f), -1.0f);
                    break;
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
                    std::uint16_t u;
                    std::memcpy(&u, p, 2);
                    value = float(u) / (a.normalized ? 65535.0f : 1.0f);
                    break;
                }
                case TINYGLTF_COMPONENT_TYPE_SHORT: {
                    std::int16_t s;
                    std::memcpy(&s, p, 2);
                    value = a.normalized ? std::max(float(s) / 32767.0f, -1.0f) : float(s);
                    break;
                }
                case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
                    std::uint32_t u;
                    std::memcpy(&u, p, 4);
                    value = float(u);
                    break;
                }
                default: fail(file, ": accessor ", index, " has component type ", a.componentType);
            }
            out[i * std::size_t(n) + std::size_t(k)] = value;
        }
    return out;
}

// Index accessor `index` as 32-bit indices.
inline std::vector<std::uint32_t> read_indices(const tinygltf::Model& m, int index, const std::string& file) {
    int n = 0;
    std::vector<float> f = read_floats(m, index, n, file);  // also checks the index and the bounds
    const tinygltf::Accessor& a = m.accessors[std::size_t(index)];
    if (n != 1) fail(file, ": index accessor ", index, " has ", n, " components, not 1");
    if (a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
        a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
        a.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
        fail(file, ": index accessor ", index, " has component type ", a.componentType, " (unsigned integers only)");
    if (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT && a.bufferView >= 0) {
        // Floats cannot hold every 32-bit index: read these directly (bounds checked above).
        const tinygltf::BufferView& v = m.bufferViews[std::size_t(a.bufferView)];
        const std::vector<unsigned char>& bytes = m.buffers[std::size_t(v.buffer)].data;
        std::size_t stride = v.byteStride ? v.byteStride : 4, first = v.byteOffset + a.byteOffset;
        std::vector<std::uint32_t> out(a.count);
        for (std::size_t i = 0; i < a.count; ++i) std::memcpy(&out[i], bytes.data() + first + i * stride, 4);
        return out;
    }
    return std::vector<std::uint32_t>(f.begin(), f.end());
}

inline glm::dmat4 node_transform(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
        glm::dmat4 t;
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 4; ++r) t[c][r] = node.matrix[std::size_t(c * 4 + r)];
        return t;
    }
    glm::dmat4 t(1.0);
    if (node.translation.size() == 3)
        t = glm::translate(t, {node.translation[0], node.translation[1], node.translation[2]});
    if (node.rotation.size() == 4)
        t *= glm::mat4_cast(glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]));
    if (node.scale.size() == 3) t = glm::scale(t, {node.scale[0], node.scale[1], node.scale[2]});
    return t;
}

inline io::texture_wrap wrap_of(int mode) {
    if (mode == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return io::texture_wrap::clamp;
    if (mode == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return io::texture_wrap::mirror;
    return io::texture_wrap::repeat;
}

// The surface texture of glTF texture `index` (its image, decoded by TinyGLTF, and its sampler).
inline io::mesh_texture texture_of(const tinygltf::Model& m, int index, const std::string& file) {
    if (index < 0 || std::size_t(index) >= m.textures.size())
        fail(file, ": texture ", index, " does not exist (the file has ", m.textures.size(), ")");
    const tinygltf::Texture& t = m.textures[std::size_t(index)];
    if (t.source < 0 || std::size_t(t.source) >= m.images.size())
        fail(file, ": texture ", index, " uses image ", t.source, " of ", m.images.size());
    const tinygltf::Image& img = m.images[std::size_t(t.source)];
    io::mesh_texture out;
    out.path = "image " + std::to_string(t.source) + (img.uri.empty() ? "" : " (" + img.uri + ")") + " of " + file;
    int channels = img.component, bytes = img.bits == 16 ? 2 : 1;
    if (img.image.empty() || img.width <= 0 || img.height <= 0 || channels < 1 || channels > 4 ||
        img.image.size() != std::size_t(img.width) * std::size_t(img.height) * std::size_t(channels * bytes))
        fail(file, ": ", out.path, " was not decoded (", img.width, " x ", img.height, ", ", channels, " channels, ",
             img.image.size(), " bytes)");
    out.width = img.width, out.height = img.height;
    out.rgba.resize(std::size_t(img.width) * std::size_t(img.height) * 4);
    for (std::size_t i = 0; i < std::size_t(img.width) * std::size_t(img.height); ++i) {
        auto at = [&](int ch) {  // the high byte of 16-bit channels (little endian)
            std::size_t byte = (i * std::size_t(channels) + std::size_t(ch)) * std::size_t(bytes);
            return img.image[byte + std::size_t(bytes - 1)];
        };
        std::uint8_t grey = at(0);
        out.rgba[4 * i + 0] = channels >= 3 ? at(0) : grey;
        out.rgba[4 * i + 1] = channels >= 3 ? at(1) : grey;
        out.rgba[4 * i + 2] = channels >= 3 ? at(2) : grey;
        out.rgba[4 * i + 3] = channels == 4 ? at(3) : (channels == 2 ? at(1) : 255);
    }
    if (t.sampler >= 0 && std::size_t(t.sampler) < m.samplers.size()) {
        out.wrap_u = wrap_of(m.samplers[std::size_t(t.sampler)].wrapS);
        out.wrap_v = wrap_of(m.samplers[std::size_t(t.sampler)].wrapT);
    }
    return out;
}

}  // namespace detail

inline io::triangle_mesh read_gltf(const std::filesystem::path& path) {
    const std::string file = path.string();
    if (!std::filesystem::exists(path)) fail("glTF file ", file, " does not exist");
    tinygltf::Model m;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    std::string ext = path.extension().string();
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    bool ok = ext == ".glb" ? loader.LoadBinaryFromFile(&m, &err, &warn, file)
                            : loader.LoadASCIIFromFile(&m, &err, &warn, file);
    if (!ok) fail("glTF file ", file, ": ", err.empty() ? std::string("cannot be read") : err);

    io::triangle_mesh mesh;
    io::mesh_surface& s = mesh.surface;
    // glTF materials first, then the white one of primitives without a material.
    std::map<int, int> texture_index;  // glTF texture -> surface texture
    for (const tinygltf::Material& gm : m.materials) {
        io::mesh_material mat;
        mat.name = gm.name.empty() ? "material " + std::to_string(s.materials.size()) : gm.name;
        const auto& factor = gm.pbrMetallicRoughness.baseColorFactor;
        for (std::size_t k = 0; k < 4 && k < factor.size(); ++k) mat.base_colour[int(k)] = float(factor[k]);
        int tex = gm.pbrMetallicRoughness.baseColorTexture.index;
        if (tex >= 0) {
            auto [it, fresh] = texture_index.emplace(tex, int(s.textures.size()));
            if (fresh) s.textures.push_back(detail::texture_of(m, tex, file));
            mat.texture = it->second;
        }
        mat.alpha = gm.alphaMode == "MASK" ? io::alpha_mode::mask
                                           : (gm.alphaMode == "BLEND" ? io::alpha_mode::blend : io::alpha_mode::opaque);
        mat.alpha_cutoff = float(gm.alphaCutoff);
        mat.double_sided = gm.doubleSided;
        s.materials.push_back(mat);
        mesh.group_names.push_back(mat.name);
    }
    const std::uint32_t white = std::uint32_t(s.materials.size());
    bool white_used = false;

    auto add_primitive = [&](const tinygltf::Primitive& p, const glm::dmat4& transform) {
        if (p.mode != TINYGLTF_MODE_TRIANGLES && p.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
            p.mode != TINYGLTF_MODE_TRIANGLE_FAN)
            return;  // points and lines: no surface
        auto position = p.attributes.find("POSITION");
        if (position == p.attributes.end()) return;
        int n = 0;
        std::vector<float> xyz = detail::read_floats(m, position->second, n, file);
        if (n != 3) fail(file, ": POSITION accessor ", position->second, " has ", n, " components, not 3");
        std::size_t vertices = xyz.size() / 3, base = mesh.positions.size();
        for (std::size_t i = 0; i < vertices; ++i) {
            glm::dvec4 w = transform * glm::dvec4(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2], 1.0);
            if (!std::isfinite(w.x) || !std::isfinite(w.y) || !std::isfinite(w.z))
                fail(file, ": POSITION accessor ", position->second, " vertex ", i, " is not finite");
            mesh.positions.push_back(glm::dvec3(w));
        }
        std::uint32_t material = p.material >= 0 ? std::uint32_t(p.material) : white;
        if (p.material >= 0 && std::size_t(p.material) >= m.materials.size())
            fail(file, ": a primitive uses material ", p.material, " of ", m.materials.size());
        white_used = white_used || p.material < 0;
        int set = material < white ? m.materials[material].pbrMetallicRoughness.baseColorTexture.texCoord : 0;
        std::vector<float> uv, colour;
        int uv_n = 0, colour_n = 0;
        if (auto it = p.attributes.find("TEXCOORD_" + std::to_string(set)); it != p.attributes.end())
            uv = detail::read_floats(m, it->second, uv_n, file);
        if (auto it = p.attributes.find("COLOR_0"); it != p.attributes.end())
            colour = detail::read_floats(m, it->second, colour_n, file);
        if (!uv.empty() && (uv_n != 2 || uv.size() != 2 * vertices))
            fail(file, ": TEXCOORD_", set, " has ", uv.size() / std::max(uv_n, 1), " elements of ", uv_n,
                 " for ", vertices, " vertices");
        if (!colour.empty() && ((colour_n != 3 && colour_n != 4) || colour.size() != std::size_t(colour_n) * vertices))
            fail(file, ": COLOR_0 has ", colour.size() / std::max(colour_n, 1), " elements of ", colour_n, " for ",
                 vertices, " vertices");
        std::vector<std::uint32_t> order;
        if (p.indices >= 0) order = detail::read_indices(m, p.indices, file);
        else for (std::uint32_t i = 0; i < vertices; ++i) order.push_back(i);
        for (std::uint32_t i : order)
            if (i >= vertices) fail(file, ": a primitive's index ", i, " is past its ", vertices, " vertices");
        auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
            mesh.triangles.push_back({std::uint32_t(base + a), std::uint32_t(base + b), std::uint32_t(base + c)});
            mesh.groups.push_back(material);
            s.triangle_materials.push_back(material);
            for (std::uint32_t k : {a, b, c}) {
                s.corner_uvs.push_back(uv.empty() ? glm::vec2(0) : glm::vec2(uv[2 * k], uv[2 * k + 1]));
                glm::vec4 col(1.0f);
                for (int ch = 0; ch < colour_n && !colour.empty(); ++ch)
                    col[ch] = colour[std::size_t(colour_n) * k + std::size_t(ch)];
                s.corner_colours.push_back(col);
            }
        };
        if (p.mode == TINYGLTF_MODE_TRIANGLES)
            for (std::size_t i = 0; i + 2 < order.size(); i += 3) add(order[i], order[i + 1], order[i + 2]);
        else if (p.mode == TINYGLTF_MODE_TRIANGLE_STRIP)
            for (std::size_t i = 0; i + 2 < order.size(); ++i)
                i % 2 ? add(order[i + 1], order[i], order[i + 2]) : add(order[i], order[i + 1], order[i + 2]);
        else
            for (std::size_t i = 1; i + 1 < order.size(); ++i) add(order[0], order[i], order[i + 1]);
    };

    // The default scene's roots (or scene 0, or every node nobody names as a child).
    std::vector<int> roots;
    int scene = m.defaultScene >= 0 ? m.defaultScene : (m.scenes.empty() ? -1 : 0);
    if (scene >= 0 && std::size_t(scene) < m.scenes.size()) roots = m.scenes[std::size_t(scene)].nodes;
    else {
        std::vector<bool> child(m.nodes.size(), false);
        for (const auto& n : m.nodes)
            for (int c : n.children)
                if (c >= 0 && std::size_t(c) < child.size()) child[std::size_t(c)] = true;
        for (std::size_t i = 0; i < m.nodes.size(); ++i)
            if (!child[i]) roots.push_back(int(i));
    }
    std::vector<std::pair<int, glm::dmat4>> stack;
    for (int r : roots) stack.push_back({r, glm::dmat4(1.0)});
    std::size_t visited = 0;
    while (!stack.empty()) {
        auto [index, parent] = stack.back();
        stack.pop_back();
        if (index < 0 || std::size_t(index) >= m.nodes.size())
            fail(file, ": node ", index, " does not exist (the file has ", m.nodes.size(), ")");
        if (++visited > 16 * m.nodes.size() + 16) fail(file, ": the node tree has a cycle");
        const tinygltf::Node& node = m.nodes[std::size_t(index)];
        glm::dmat4 t = parent * detail::node_transform(node);
        if (node.mesh >= 0) {
            if (std::size_t(node.mesh) >= m.meshes.size())
                fail(file, ": node ", index, " uses mesh ", node.mesh, " of ", m.meshes.size());
            for (const tinygltf::Primitive& p : m.meshes[std::size_t(node.mesh)].primitives) add_primitive(p, t);
        }
        for (int c : node.children) stack.push_back({c, t});
    }
    if (white_used) {
        s.materials.emplace_back().name = "(no material)";
        mesh.group_names.push_back("(no material)");
    }
    if (mesh.group_names.empty()) mesh.group_names.push_back("default");
    if (mesh.triangles.empty()) fail("glTF file ", file, ": no triangles in its scene");
    bool any_colour = false;
    for (const glm::vec4& c : s.corner_colours) any_colour = any_colour || c != glm::vec4(1.0f);
    if (!any_colour) s.corner_colours.clear();
    mesh.validate();
    return mesh;
}

}  // namespace voxray::gltf
