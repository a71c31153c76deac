#include "mesh_export.hpp"

#include <cstring>
#include <filesystem>
#include <tiny_gltf.h>

#include "output.hpp"
#include "voxray/meshing/quad_corners.hpp"
#include "voxray/scenes/noise.hpp"

namespace voxray::tool {

namespace {

// The quads drawn at `level` as corner positions (4 per quad, wound counter-clockwise seen
// from outside) and one colour per quad: the palette's, or a colour from the material
// number where the palette has none (the built-in scenes).
struct flat_mesh {
    std::vector<float> positions;       // 3 per corner
    std::vector<std::uint8_t> colours;  // 4 per corner
    std::size_t quads() const { return positions.size() / 12; }
};

flat_mesh flatten(const std::vector<meshing::chunk_mesh>& meshes, const palette& colours, int level) {
    flat_mesh out;
    for (auto& m : meshes)
        meshing::for_each_quad_at(m, level, [&](std::uint32_t i, const std::array<glm::ivec3, 4>& corners) {
            std::uint32_t material = VX_MESH_MATERIAL(m.words[2 * i + 1]);
            rgba c = colours[std::uint8_t(material)].colour;
            if (!c.r && !c.g && !c.b) {
                auto h = scenes::mix64(material + 1);
                c = {std::uint8_t(64 + (h & 127)), std::uint8_t(64 + ((h >> 8) & 127)),
                     std::uint8_t(64 + ((h >> 16) & 127)), 255};
            }
            for (const glm::ivec3& p : corners) {
                out.positions.insert(out.positions.end(), {float(p.x), float(p.y), float(p.z)});
                out.colours.insert(out.colours.end(), {c.r, c.g, c.b, 255});
            }
        });
    return out;
}

}  // namespace

void write_mesh_ply(const std::string& path, const std::vector<meshing::chunk_mesh>& meshes, const palette& colours, int level) {
    flat_mesh f = flatten(meshes, colours, level);
    output_file out(path, "--ply");
    auto& s = out.stream();
    s << "ply\nformat binary_little_endian 1.0\ncomment voxray chunk meshes, level of detail " << level << "\n"
      << "element vertex " << f.quads() * 4 << "\nproperty float x\nproperty float y\nproperty float z\n"
      << "property uchar red\nproperty uchar green\nproperty uchar blue\nproperty uchar alpha\n"
      << "element face " << f.quads() << "\nproperty list uchar uint vertex_indices\nend_header\n";
    for (std::size_t v = 0; v < f.quads() * 4; ++v) {
        s.write(reinterpret_cast<const char*>(&f.positions[3 * v]), 12);
        s.write(reinterpret_cast<const char*>(&f.colours[4 * v]), 4);
    }
    for (std::uint32_t q = 0; q < f.quads(); ++q) {
        std::uint8_t four = 4;
        std::uint32_t index[4] = {4 * q, 4 * q + 1, 4 * q + 2, 4 * q + 3};
        s.write(reinterpret_cast<const char*>(&four), 1);
        s.write(reinterpret_cast<const char*>(index), sizeof index);
    }
    out.finish();
}

void write_mesh_gltf(const std::string& path, const std::vector<meshing::chunk_mesh>& meshes, const palette& colours, int level) {
    flat_mesh f = flatten(meshes, colours, level);
    std::vector<std::uint32_t> indices;
    for (std::uint32_t q = 0; q < f.quads(); ++q)
        indices.insert(indices.end(), {4 * q, 4 * q + 1, 4 * q + 2, 4 * q, 4 * q + 2, 4 * q + 3});
    tinygltf::Model model;
    tinygltf::Buffer buffer;
    auto append = [&](const void* data, std::size_t bytes) {
        std::size_t at = buffer.data.size();
        buffer.data.resize(at + bytes);
        if (bytes) std::memcpy(buffer.data.data() + at, data, bytes);
        return at;
    };
    auto add_view = [&](const void* data, std::size_t bytes, int target) {
        tinygltf::BufferView view;
        view.buffer = 0, view.byteOffset = append(data, bytes), view.byteLength = bytes, view.target = target;
        model.bufferViews.push_back(view);
        return int(model.bufferViews.size() - 1);
    };
    auto add_accessor = [&](int view, int component, int type, std::size_t count, bool normalized) {
        tinygltf::Accessor a;
        a.bufferView = view, a.componentType = component, a.type = type, a.count = count, a.normalized = normalized;
        model.accessors.push_back(a);
        return int(model.accessors.size() - 1);
    };
    std::size_t corners = f.quads() * 4;
    int positions = add_accessor(add_view(f.positions.data(), f.positions.size() * 4, TINYGLTF_TARGET_ARRAY_BUFFER),
                                 TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, corners, false);
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (std::size_t v = 0; v < corners; ++v)
        for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], f.positions[3 * v + a]), hi[a] = std::max(hi[a], f.positions[3 * v + a]);
    if (corners) model.accessors[positions].minValues = {lo.x, lo.y, lo.z}, model.accessors[positions].maxValues = {hi.x, hi.y, hi.z};
    int colour = add_accessor(add_view(f.colours.data(), f.colours.size(), TINYGLTF_TARGET_ARRAY_BUFFER),
                              TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE, TINYGLTF_TYPE_VEC4, corners, true);
    int index = add_accessor(add_view(indices.data(), indices.size() * 4, TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER),
                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR, indices.size(), false);
    model.buffers.push_back(std::move(buffer));
    tinygltf::Primitive primitive;
    primitive.attributes = {{"POSITION", positions}, {"COLOR_0", colour}};
    primitive.indices = index, primitive.mode = TINYGLTF_MODE_TRIANGLES;
    tinygltf::Mesh mesh;
    mesh.name = "voxray chunk meshes, level of detail " + std::to_string(level);
    mesh.primitives.push_back(primitive);
    model.meshes.push_back(mesh);
    tinygltf::Node node;
    node.mesh = 0;
    model.nodes.push_back(node);
    tinygltf::Scene scene;
    scene.nodes = {0};
    model.scenes.push_back(scene);
    model.defaultScene = 0;
    model.asset.version = "2.0", model.asset.generator = "voxray";
    bool binary = std::filesystem::path(path).extension() == ".glb";
    tinygltf::TinyGLTF writer;
    if (!writer.WriteGltfSceneToFile(&model, path, false, true, !binary, binary)) fail("--gltf ", path, ": cannot be written");
}

}  // namespace voxray::tool
