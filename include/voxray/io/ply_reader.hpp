// Stanford PLY reader: ASCII, binary little endian and binary big endian.
// Reads the 'vertex' element's x, y, z (any scalar type) and the 'face' element's
// index list ('vertex_indices' or 'vertex_index'; integer count and item types),
// fanning polygons into triangles. Every other element and property is skipped,
// which in binary files means walking it byte by byte, so all are parsed.
//
//   ply
//   format binary_little_endian 1.0
//   element vertex 8            <- count known up front: indices are checked at once
//   property float x            ...y, z, and any others (skipped)
//   element face 12
//   property list uchar int vertex_indices
//   end_header                  <- binary data starts on the next byte
//
// Errors name the file and the header/ASCII line or the binary byte offset.
#pragma once
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/io/mesh.hpp"
#include "voxray/io/mesh_text.hpp"

namespace voxray::io {

namespace detail {

// A header longer than this is not a mesh header (or has no end_header).
inline constexpr std::size_t ply_max_header_bytes = 64 * 1024;

enum class ply_type : std::uint8_t { none, i8, u8, i16, u16, i32, u32, f32, f64 };

inline ply_type ply_type_from(std::string_view s) {
    if (s == "char" || s == "int8") return ply_type::i8;
    if (s == "uchar" || s == "uint8") return ply_type::u8;
    if (s == "short" || s == "int16") return ply_type::i16;
    if (s == "ushort" || s == "uint16") return ply_type::u16;
    if (s == "int" || s == "int32") return ply_type::i32;
    if (s == "uint" || s == "uint32") return ply_type::u32;
    if (s == "float" || s == "float32") return ply_type::f32;
    if (s == "double" || s == "float64") return ply_type::f64;
    return ply_type::none;
}
inline int ply_size(ply_type t) {
    constexpr int sizes[] = {0, 1, 1, 2, 2, 4, 4, 4, 8};
    return sizes[int(t)];
}
inline bool ply_is_integer(ply_type t) { return t != ply_type::f32 && t != ply_type::f64; }

struct ply_property {
    std::string name;
    ply_type type = ply_type::none;        // item type for lists
    ply_type count_type = ply_type::none;  // none: a scalar property
};

struct ply_element {
    std::string name;
    std::uint64_t count = 0;
    std::vector<ply_property> props;
    std::size_t min_bytes = 0;  // binary size of one instance with all lists empty
};

// Binary values: the byte order is fixed by the header.
class ply_binary_source {
public:
    ply_binary_source(std::string_view data, std::size_t start, bool big_endian, const std::string& name)
        : data_(data), pos_(start), big_(big_endian), name_(name) {}

    void begin(const ply_element&, std::uint64_t) {}
    void end() {}
    double value(ply_type t) {
        value_pos_ = pos_;
        int n = ply_size(t);
        if (data_.size() - pos_ < std::size_t(n))
            fail(name_, ": truncated binary data at byte offset ", pos_, " (", data_.size() - pos_,
                 " bytes left, value needs ", n, ")");
        unsigned char b[8];
        std::memcpy(b, data_.data() + pos_, std::size_t(n));
        pos_ += std::size_t(n);
        if (big_ != (std::endian::native == std::endian::big))
            for (int i = 0; i < n / 2; ++i) std::swap(b[i], b[n - 1 - i]);
        switch (t) {
            case ply_type::i8: return double(std::int8_t(b[0]));
            case ply_type::u8: return double(b[0]);
            case ply_type::i16: { std::int16_t v; std::memcpy(&v, b, 2); return v; }
            case ply_type::u16: { std::uint16_t v; std::memcpy(&v, b, 2); return v; }
            case ply_type::i32: { std::int32_t v; std::memcpy(&v, b, 4); return v; }
            case ply_type::u32: { std::uint32_t v; std::memcpy(&v, b, 4); return v; }
            case ply_type::f32: { float v; std::memcpy(&v, b, 4); return v; }
            default: { double v; std::memcpy(&v, b, 8); return v; }
        }
    }
    // Refuses counts that cannot fit in the bytes left, before anything is allocated.
    void expect(const ply_element& e) const {
        std::size_t left = data_.size() - pos_;
        if (e.min_bytes && e.count > left / e.min_bytes)
            fail(name_, ": truncated binary data at byte offset ", pos_, ": ", e.count, " '", e.name,
                 "' elements need at least ", e.min_bytes, " bytes each, ", left, " bytes left");
    }
    std::string where() const { return name_ + ": byte offset " + std::to_string(value_pos_); }

private:
    std::string_view data_;
    std::size_t pos_, value_pos_ = 0;
    bool big_;
    const std::string& name_;
};

// ASCII values: one element instance per line, whitespace-separated.
class ply_ascii_source {
public:
    ply_ascii_source(std::string_view text, line_cursor lines, const std::string& name)
        : text_(text), lines_(lines), name_(name) {}

    void begin(const ply_element& e, std::uint64_t i) {
        do {
            if (!lines_.next(rest_))
                fail(name_, ":", lines_.line_number() + 1, ": unexpected end of file in '", e.name, "' element ", i,
                     " of ", e.count);
            while (!rest_.empty() && is_space(rest_.front())) rest_.remove_prefix(1);
        } while (rest_.empty());  // blank lines carry nothing
    }
    void end() {
        auto tok = next_token(rest_);
        if (!tok.empty()) fail(where(), ": unexpected extra value ", quote(tok));
    }
    double value(ply_type t) {
        auto tok = next_token(rest_);
        if (tok.empty()) fail(where(), ": line ends early, a value is missing");
        if (ply_is_integer(t)) {
            std::int64_t v;
            if (!parse_number(tok, v)) fail(where(), ": bad integer value ", quote(tok));
            return double(v);
        }
        double v;
        if (!parse_number(tok, v)) fail(where(), ": bad number ", quote(tok));
        return v;
    }
    void expect(const ply_element& e) const {
        std::size_t left = text_.size() - lines_.offset();
        if (e.count > left / 2 + 1)  // an instance takes at least a value and a separator
            fail(where(), ": '", e.name, "' declares ", e.count, " elements but only ", left, " bytes follow");
    }
    std::string where() const { return name_ + ":" + std::to_string(lines_.line_number()); }

private:
    std::string_view text_;
    line_cursor lines_;
    std::string_view rest_;
    const std::string& name_;
};

// Reads every element in header order; keeps vertex positions and face polygons.
template <class Source>
void read_ply_body(Source& src, const std::vector<ply_element>& elements, std::uint64_t vertex_count,
                   triangle_mesh& mesh) {
    std::vector<std::uint32_t> polygon;
    for (auto& e : elements) {
        src.expect(e);
        bool is_vertex = e.name == "vertex", is_face = e.name == "face";
        int coord_of[64];  // property index -> 0,1,2 for x,y,z, else -1
        for (std::size_t p = 0; p < e.props.size() && p < 64; ++p) {
            auto& n = e.props[p].name;
            coord_of[p] = !is_vertex ? -1 : n == "x" ? 0 : n == "y" ? 1 : n == "z" ? 2 : -1;
        }
        if (is_vertex) mesh.positions.reserve(std::size_t(e.count));
        for (std::uint64_t i = 0; i < e.count; ++i) {
            src.begin(e, i);
            glm::dvec3 pos(0.0);
            for (std::size_t p = 0; p < e.props.size(); ++p) {
                auto& prop = e.props[p];
                if (prop.count_type == ply_type::none) {
                    double v = src.value(prop.type);
                    if (p < 64 && coord_of[p] >= 0) {
                        if (!std::isfinite(v)) fail(src.where(), ": non-finite vertex coordinate ", v);
                        pos[coord_of[p]] = v;
                    }
                    continue;
                }
                double n = src.value(prop.count_type);
                if (n < 0) fail(src.where(), ": negative list length ", n);
                bool indices = is_face && (prop.name == "vertex_indices" || prop.name == "vertex_index");
                polygon.clear();
                for (double k = 0; k < n; ++k) {
                    double v = src.value(prop.type);
                    if (!indices) continue;
                    if (v < 0 || v >= double(vertex_count))
                        fail(src.where(), ": vertex index ", std::int64_t(v), " out of range (", vertex_count,
                             " vertices)");
                    polygon.push_back(std::uint32_t(v));
                }
                if (!indices) continue;
                if (polygon.size() < 3) fail(src.where(), ": face has ", polygon.size(), " vertices, needs at least 3");
                for (std::size_t k = 1; k + 1 < polygon.size(); ++k) {
                    mesh.triangles.push_back({polygon[0], polygon[k], polygon[k + 1]});
                    mesh.groups.push_back(0);
                }
            }
            src.end();
            if (is_vertex) mesh.positions.push_back(pos);
        }
    }
}

}  // namespace detail

// Parses PLY bytes; `name` is used in error messages (normally the path).
inline triangle_mesh parse_ply(std::string_view bytes, const std::string& name) {
    using namespace detail;
    auto header_end = bytes.find("end_header");
    if (bytes.substr(0, 3) != "ply") fail(name, ": not a PLY file (no 'ply' magic)");
    if (header_end == std::string_view::npos || header_end > ply_max_header_bytes)
        fail(name, ": PLY header too long (no end_header in the first ", ply_max_header_bytes, " bytes)");

    enum { ascii, little, big, unknown } format = unknown;
    std::vector<ply_element> elements;
    line_cursor lines(bytes);
    std::string_view line;
    bool done = false;
    while (!done && lines.next(line)) {
        auto at = [&] { return name + ":" + std::to_string(lines.line_number()); };
        std::string_view rest = line;
        auto key = next_token(rest);
        if (lines.line_number() == 1) {
            if (key != "ply") fail(at(), ": not a PLY file (no 'ply' magic)");
        } else if (key == "format") {
            auto f = next_token(rest);
            format = f == "ascii" ? ascii : f == "binary_little_endian" ? little : f == "binary_big_endian" ? big : unknown;
            if (format == unknown) fail(at(), ": unsupported PLY format ", quote(f));
        } else if (key == "element") {
            ply_element e;
            e.name = std::string(next_token(rest));
            auto count_text = next_token(rest);
            std::int64_t count;
            if (!parse_number(count_text, count) || count < 0 || count > std::int64_t(UINT32_MAX))
                fail(at(), ": bad element count ", quote(count_text));
            e.count = std::uint64_t(count);
            elements.push_back(std::move(e));
        } else if (key == "property") {
            if (elements.empty()) fail(at(), ": property before any element");
            auto& e = elements.back();
            ply_property p;
            auto type_text = next_token(rest);
            if (type_text == "list") {
                auto count_type = next_token(rest);
                auto item_type = next_token(rest);
                p.count_type = ply_type_from(count_type);
                p.type = ply_type_from(item_type);
                if (p.count_type == ply_type::none || !ply_is_integer(p.count_type))
                    fail(at(), ": unsupported PLY list count type ", quote(count_type));
                if (p.type == ply_type::none) fail(at(), ": unsupported PLY property type ", quote(item_type));
                e.min_bytes += std::size_t(ply_size(p.count_type));
            } else {
                p.type = ply_type_from(type_text);
                if (p.type == ply_type::none) fail(at(), ": unsupported PLY property type ", quote(type_text));
                e.min_bytes += std::size_t(ply_size(p.type));
            }
            p.name = std::string(next_token(rest));
            bool index_list = e.name == "face" && (p.name == "vertex_indices" || p.name == "vertex_index");
            if (index_list && p.count_type == ply_type::none) fail(at(), ": face property ", p.name, " is not a list");
            if (index_list && !ply_is_integer(p.type))
                fail(at(), ": unsupported PLY index type ", quote(type_text == "list" ? "float" : type_text),
                     " (face indices must be integers)");
            if (e.name == "vertex" && (p.name == "x" || p.name == "y" || p.name == "z") &&
                p.count_type != ply_type::none)
                fail(at(), ": vertex coordinate ", p.name, " is a list");
            // Each coordinate once: 'x y y' would otherwise leave z silently 0.
            if (e.name == "vertex" && (p.name == "x" || p.name == "y" || p.name == "z"))
                for (auto& q : e.props)
                    if (q.name == p.name) fail(at(), ": vertex coordinate ", p.name, " is declared twice");
            if (e.props.size() >= 64) fail(at(), ": element '", e.name, "' has more than 64 properties");
            e.props.push_back(std::move(p));
        } else if (key == "end_header") {
            done = true;
        } else if (key != "comment" && key != "obj_info" && !key.empty()) {
            fail(at(), ": unknown PLY header keyword ", quote(key));
        }
    }
    if (format == unknown) fail(name, ": PLY header has no format line");

    std::uint64_t vertex_count = 0;
    bool has_xyz = false, has_faces = false;
    for (auto& e : elements) {
        if (e.name == "vertex") {
            vertex_count = e.count;
            int found = 0;
            for (auto& p : e.props) found += p.name == "x" || p.name == "y" || p.name == "z";
            has_xyz = found == 3;
        }
        if (e.name == "face")
            for (auto& p : e.props) has_faces |= p.name == "vertex_indices" || p.name == "vertex_index";
    }
    if (!has_xyz) fail(name, ": PLY has no 'vertex' element with x, y and z");
    if (!has_faces) fail(name, ": no triangles (PLY has no 'face' element with vertex_indices)");

    triangle_mesh mesh;
    if (format == ascii) {
        ply_ascii_source src(bytes, lines, name);
        read_ply_body(src, elements, vertex_count, mesh);
    } else {
        ply_binary_source src(bytes, lines.offset(), format == big, name);
        read_ply_body(src, elements, vertex_count, mesh);
    }
    if (mesh.triangles.empty()) fail(name, ": no triangles (", mesh.positions.size(), " vertices, 0 faces)");
    auto stem = std::filesystem::path(name).stem().string();
    mesh.group_names.push_back(stem.empty() ? "ply" : stem);
    return mesh;
}

inline triangle_mesh read_ply(const std::filesystem::path& path) {
    auto bytes = detail::read_whole_file(path);
    return parse_ply(bytes, path.string());
}

}  // namespace voxray::io
