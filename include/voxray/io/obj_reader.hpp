// Wavefront OBJ reader: positions ('v'), faces ('f', polygons fanned into
// triangles) and groups ('g' / 'o' names, which become palette colours). With
// obj_options::materials also texture coordinates ('vt', v flipped to point down, as
// io/mesh_surface.hpp has it), 'mtllib' files (io/mtl_reader.hpp, relative to the OBJ) and
// 'usemtl', as the mesh's coloured surface; without it, or when the file names no material,
// the mesh has no colour. Normals and everything else are skipped.
//
// Indices follow the OBJ rules: 1-based, negative = relative to the vertices read
// so far (-1 is the latest). A positive index may point at a vertex defined later
// in the file (some exporters do that), so those are checked once at the end.
// Every error names the file, the line and the offending text.
#pragma once
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/io/mesh.hpp"
#include "voxray/io/mesh_text.hpp"
#include "voxray/io/mtl_reader.hpp"

namespace voxray::io {

struct obj_options {
    bool materials = false;  // read texture coordinates and materials (the coloured surface)
};

// Parses OBJ text; `name` is used in error messages (normally the path); `folder` is where
// mtllib files are looked for.
inline triangle_mesh parse_obj(std::string_view text, const std::string& name, const obj_options& options = {},
                               const std::filesystem::path& folder = {}) {
    using namespace detail;
    triangle_mesh mesh;
    // The coloured surface: texture coordinates, materials by name, the current one.
    std::vector<glm::vec2> uvs;
    std::unordered_map<std::string, std::uint32_t> material_index;
    std::int64_t material = -1;           // -1: no usemtl yet
    std::vector<std::int64_t> polygon_uvs;  // per corner: resolved vt index, or -1
    std::vector<std::int64_t> triangle_material;
    std::vector<std::int64_t> corner_uv;    // 3 per triangle
    bool any_material = false;
    std::unordered_map<std::string, std::uint32_t> group_ids;
    std::uint32_t group = 0;
    bool group_open = false;  // "default" is created only when a face needs it
    auto use_group = [&](std::string gname) {
        if (gname.empty()) gname = "default";
        auto [it, fresh] = group_ids.emplace(gname, std::uint32_t(mesh.group_names.size()));
        if (fresh) mesh.group_names.push_back(gname);
        group = it->second;
        group_open = true;
    };

    struct forward_ref {
        std::int64_t index;
        std::size_t line;
    };
    std::vector<forward_ref> forward;   // positive indices past the vertices read so far
    std::vector<std::uint32_t> polygon;  // resolved indices of the current face

    line_cursor lines(text);
    std::string_view line;
    while (lines.next(line)) {
        auto at = [&] { return name + ":" + std::to_string(lines.line_number()); };
        std::string_view rest = line;
        auto key = next_token(rest);
        if (key == "v") {
            glm::dvec3 p;
            for (int k = 0; k < 3; ++k) {
                auto tok = next_token(rest);
                if (tok.empty()) fail(at(), ": vertex has ", k, " coordinates, needs 3");
                if (!parse_number(tok, p[k])) fail(at(), ": bad vertex coordinate ", quote(tok));
                if (!std::isfinite(p[k])) fail(at(), ": non-finite vertex coordinate ", quote(tok));
            }
            if (mesh.positions.size() >= std::numeric_limits<std::uint32_t>::max())
                fail(at(), ": more than ", std::numeric_limits<std::uint32_t>::max(), " vertices");
            mesh.positions.push_back(p);
        } else if (key == "vt" && options.materials) {
            double u = 0, v = 0;
            auto tu = next_token(rest), tv = next_token(rest);
            if (!parse_number(tu, u) || !std::isfinite(u)) fail(at(), ": bad texture coordinate ", quote(tu));
            if (!tv.empty() && (!parse_number(tv, v) || !std::isfinite(v)))
                fail(at(), ": bad texture coordinate ", quote(tv));
            uvs.push_back({float(u), float(1.0 - v)});
        } else if (key == "mtllib" && options.materials) {
            for (auto tok = next_token(rest); !tok.empty(); tok = next_token(rest)) {
                auto file = folder / std::filesystem::path(std::string(tok));
                if (!std::filesystem::exists(file)) fail(at(), ": material library ", file.string(), " does not exist");
                read_mtl(file, mesh.surface, material_index);
            }
        } else if (key == "usemtl" && options.materials) {
            auto material_name = trimmed(rest);
            auto it = material_index.find(std::string(material_name));
            if (it == material_index.end())
                fail(at(), ": usemtl ", quote(material_name), ": no such material in the mtllib files read so far");
            material = it->second;
            any_material = true;
        } else if (key == "f") {
            polygon.clear();
            polygon_uvs.clear();
            for (auto tok = next_token(rest); !tok.empty(); tok = next_token(rest)) {
                auto index_text = tok.substr(0, tok.find('/'));  // "7/2/5" -> "7"
                if (options.materials) {
                    std::int64_t uv = -1;
                    auto slash = tok.find('/');
                    if (slash != std::string_view::npos) {
                        auto uv_text = tok.substr(slash + 1);
                        uv_text = uv_text.substr(0, uv_text.find('/'));
                        std::int64_t vt = 0;
                        if (!uv_text.empty()) {
                            if (!parse_number(uv_text, vt)) fail(at(), ": bad texture coordinate index ", quote(tok));
                            auto have = std::int64_t(uvs.size());
                            uv = vt > 0 ? vt - 1 : have + vt;
                            if (vt == 0 || uv < 0 || uv >= have)
                                fail(at(), ": texture coordinate index ", vt, " out of range (", have, " so far)");
                        }
                    }
                    polygon_uvs.push_back(uv);
                }
                std::int64_t idx = 0;
                if (!parse_number(index_text, idx)) fail(at(), ": bad face index ", quote(tok));
                auto have = std::int64_t(mesh.positions.size());
                std::int64_t resolved = idx > 0 ? idx - 1 : have + idx;
                if (idx == 0 || resolved < 0)
                    fail(at(), ": face index ", idx, " out of range (", have, " vertices so far)");
                if (resolved >= have) {
                    if (resolved >= std::int64_t(std::numeric_limits<std::uint32_t>::max()))
                        fail(at(), ": face index ", idx, " out of range");
                    forward.push_back({idx, lines.line_number()});
                }
                polygon.push_back(std::uint32_t(resolved));
            }
            if (polygon.size() < 3) fail(at(), ": face has ", polygon.size(), " vertices, needs at least 3");
            if (!group_open) use_group("default");
            for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {  // fan around the first vertex
                mesh.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
                mesh.groups.push_back(group);
                if (options.materials) {
                    triangle_material.push_back(material);
                    for (std::size_t c : {std::size_t(0), k, k + 1}) corner_uv.push_back(polygon_uvs[c]);
                }
            }
        } else if (key == "g" || key == "o") {
            use_group(std::string(trimmed(rest)));
        }
        // Anything else (vt, vn, s, usemtl, mtllib, l, p, comments) carries no shape.
    }

    for (auto& f : forward)
        if (f.index > std::int64_t(mesh.positions.size()))
            fail(name, ":", f.line, ": face index ", f.index, " out of range (file has ", mesh.positions.size(),
                 " vertices)");
    if (mesh.triangles.empty()) fail(name, ": no triangles (", mesh.positions.size(), " vertices, no faces)");
    if (any_material) {
        // Faces before the first usemtl take a white material of their own.
        std::uint32_t plain = std::uint32_t(mesh.surface.materials.size());
        bool plain_used = false;
        for (std::int64_t m : triangle_material) {
            plain_used = plain_used || m < 0;
            mesh.surface.triangle_materials.push_back(m < 0 ? plain : std::uint32_t(m));
        }
        if (plain_used) mesh.surface.materials.emplace_back().name = "(no usemtl)";
        bool any_uv = false;
        for (std::int64_t i : corner_uv) any_uv = any_uv || i >= 0;
        if (any_uv)
            for (std::int64_t i : corner_uv)
                mesh.surface.corner_uvs.push_back(i >= 0 ? uvs[std::size_t(i)] : glm::vec2(0));
    } else {
        mesh.surface = {};  // no usemtl: no colour (the groups' palette)
    }
    return mesh;
}

inline triangle_mesh read_obj(const std::filesystem::path& path, const obj_options& options = {}) {
    auto text = detail::read_whole_file(path);
    return parse_obj(text, path.string(), options, path.parent_path());
}

}  // namespace voxray::io
