// Wavefront OBJ reader: positions ('v'), faces ('f', polygons fanned into
// triangles) and groups ('g' / 'o' names, which become palette colours).
// Texture coordinates, normals, materials and everything else are skipped: the
// voxelizer needs shape and grouping only.
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

namespace voxray::io {

// Parses OBJ text; `name` is used in error messages (normally the path).
inline triangle_mesh parse_obj(std::string_view text, const std::string& name) {
    using namespace detail;
    triangle_mesh mesh;
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
        } else if (key == "f") {
            polygon.clear();
            for (auto tok = next_token(rest); !tok.empty(); tok = next_token(rest)) {
                auto index_text = tok.substr(0, tok.find('/'));  // "7/2/5" -> "7"
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
            }
        } else if (key == "g" || key == "o") {
            while (!rest.empty() && is_space(rest.front())) rest.remove_prefix(1);
            while (!rest.empty() && is_space(rest.back())) rest.remove_suffix(1);
            use_group(std::string(rest));
        }
        // Anything else (vt, vn, s, usemtl, mtllib, l, p, comments) carries no shape.
    }

    for (auto& f : forward)
        if (f.index > std::int64_t(mesh.positions.size()))
            fail(name, ":", f.line, ": face index ", f.index, " out of range (file has ", mesh.positions.size(),
                 " vertices)");
    if (mesh.triangles.empty()) fail(name, ": no triangles (", mesh.positions.size(), " vertices, no faces)");
    return mesh;
}

inline triangle_mesh read_obj(const std::filesystem::path& path) {
    auto text = detail::read_whole_file(path);
    return parse_obj(text, path.string());
}

}  // namespace voxray::io
