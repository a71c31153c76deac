// Small text-scanning helpers shared by the OBJ and PLY readers: whole-file read,
// line iteration with line numbers, whitespace tokens and strict number parsing.
// std::from_chars keeps parsing locale-free and fast (no istream per number).
#pragma once
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>

#include "voxray/core/error.hpp"

namespace voxray::io::detail {

// Mesh files beyond this are refused before any allocation: a guard against a
// path that names a device or a huge unrelated file.
inline constexpr std::uintmax_t max_mesh_file_bytes = std::uintmax_t(4) << 30;

inline std::string read_whole_file(const std::filesystem::path& path) {
    std::error_code ec;
    auto size = std::filesystem::file_size(path, ec);
    if (ec) fail("mesh file ", path.string(), ": cannot read (", ec.message(), ")");
    if (size > max_mesh_file_bytes)
        fail("mesh file ", path.string(), ": size ", size, " bytes is above the limit of ", max_mesh_file_bytes);
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("mesh file ", path.string(), ": cannot open");
    std::string bytes(size, '\0');
    in.read(bytes.data(), std::streamsize(size));
    if (std::uintmax_t(in.gcount()) != size) fail("mesh file ", path.string(), ": short read");
    return bytes;
}

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// Iterates over the lines of a text, counting from 1. The returned view excludes
// the newline and any trailing '\r'.
class line_cursor {
public:
    explicit line_cursor(std::string_view text, std::size_t start = 0) : text_(text), pos_(start) {}

    bool next(std::string_view& line) {
        if (pos_ >= text_.size()) return false;
        auto end = text_.find('\n', pos_);
        if (end == std::string_view::npos) end = text_.size();
        line = text_.substr(pos_, end - pos_);
        while (!line.empty() && line.back() == '\r') line.remove_suffix(1);
        pos_ = end + 1;
        ++line_;
        return true;
    }
    std::size_t line_number() const { return line_; }
    // Byte offset just past the current line (where binary PLY data starts).
    std::size_t offset() const { return pos_ < text_.size() ? pos_ : text_.size(); }

private:
    std::string_view text_;
    std::size_t pos_ = 0;
    std::size_t line_ = 0;
};

// Splits off the next whitespace-separated token; empty when none is left.
inline std::string_view next_token(std::string_view& rest) {
    std::size_t i = 0;
    while (i < rest.size() && is_space(rest[i])) ++i;
    std::size_t j = i;
    while (j < rest.size() && !is_space(rest[j])) ++j;
    auto tok = rest.substr(i, j - i);
    rest.remove_prefix(j);
    return tok;
}

// `s` without its leading and trailing whitespace (a name that may hold spaces).
inline std::string_view trimmed(std::string_view s) {
    while (!s.empty() && is_space(s.front())) s.remove_prefix(1);
    while (!s.empty() && is_space(s.back())) s.remove_suffix(1);
    return s;
}

// Whole-token parses: "1.5x" or "" fail rather than reading a prefix.
inline bool parse_number(std::string_view tok, double& out) {
    if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
    auto [p, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out);
    return ec == std::errc() && p == tok.data() + tok.size() && !tok.empty();
}
inline bool parse_number(std::string_view tok, std::int64_t& out) {
    if (!tok.empty() && tok.front() == '+') tok.remove_prefix(1);
    auto [p, ec] = std::from_chars(tok.data(), tok.data() + tok.size(), out);
    return ec == std::errc() && p == tok.data() + tok.size() && !tok.empty();
}

// Short printable form of a token for error messages (binary junk stays readable).
inline std::string quote(std::string_view tok) {
    std::string s = "'";
    for (char c : tok.substr(0, 40)) s += (c >= 32 && c < 127) ? c : '?';
    if (tok.size() > 40) s += "...";
    return s + "'";
}

}  // namespace voxray::io::detail
