// Checked little-endian reads over a byte span, for the .vox reader.
//
// Every read goes through `need(n)`, which compares n with the bytes left *before*
// touching memory, so a lying size field can never make the reader step outside the
// buffer. A failed check throws voxray::error naming the file, the absolute byte
// offset, the chunk being read and the value that did not fit, e.g.
//
//   scene.vox: byte 1234 in chunk 'XYZI': voxel count 1000000 needs 4000000 bytes, 400 left
//
// A cursor covers one window [begin, end) of the file (usually one chunk's content);
// offsets in messages are absolute positions in the file.
#pragma once
#include <charconv>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>

#include "voxray/core/error.hpp"

namespace voxray::io {

// A chunk id as text for messages; bytes that are not printable ASCII become \xNN.
inline std::string vox_chunk_name(std::span<const std::uint8_t, 4> id) {
    static constexpr char hex[] = "0123456789abcdef";
    std::string s;
    for (std::uint8_t c : id) {
        if (c >= 0x20 && c < 0x7f && c != '\\' && c != '\'') {
            s += char(c);
        } else {
            s += "\\x";
            s += hex[c >> 4];
            s += hex[c & 15];
        }
    }
    return s;
}

// At most 40 characters of a (possibly hostile) string value, for messages.
inline std::string vox_quote(std::string_view v) {
    std::string s = "\"";
    for (char c : v.substr(0, 40)) s += (c >= 0x20 && c < 0x7f) ? c : '?';
    return s + (v.size() > 40 ? "...\"" : "\"");
}

class vox_cursor {
public:
    vox_cursor(std::span<const std::uint8_t> file, std::size_t begin, std::size_t end, std::string_view file_name,
               std::string chunk = {})
        : file_(file), pos_(begin), end_(end), name_(file_name), chunk_(std::move(chunk)) {
        if (begin > end || end > file.size()) fail(name_, ": internal error: cursor window out of range");
    }

    std::size_t offset() const { return pos_; }
    std::size_t left() const { return end_ - pos_; }
    std::string_view file_name() const { return name_; }
    const std::string& chunk() const { return chunk_; }

    // Throws with the file, the current offset and the chunk in the message.
    template <class... Parts>
    [[noreturn]] void error(Parts&&... parts) const {
        error_at(pos_, std::forward<Parts>(parts)...);
    }
    template <class... Parts>
    [[noreturn]] void error_at(std::size_t at, Parts&&... parts) const {
        if (chunk_.empty()) fail(name_, ": byte ", at, ": ", std::forward<Parts>(parts)...);
        fail(name_, ": byte ", at, " in chunk '", chunk_, "': ", std::forward<Parts>(parts)...);
    }

    // Throws unless n more bytes are available; `what` names the field being read.
    void need(std::uint64_t n, const char* what) const {
        if (n > left()) error("truncated ", what, ": needs ", n, " bytes, ", left(), " left");
    }

    std::uint32_t u32(const char* what) {
        need(4, what);
        auto* p = file_.data() + pos_;
        pos_ += 4;
        return std::uint32_t(p[0]) | std::uint32_t(p[1]) << 8 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[3]) << 24;
    }
    std::int32_t i32(const char* what) { return std::int32_t(u32(what)); }

    // A count that must be >= 0 and whose items take at least `min_item_bytes` each, so
    // a hostile count is rejected before anything is allocated for it.
    std::uint32_t count(const char* what, std::uint32_t min_item_bytes) {
        auto at = pos_;
        auto n = i32(what);
        if (n < 0) error_at(at, what, " is negative (", n, ")");
        if (std::uint64_t(n) * min_item_bytes > left())
            error_at(at, what, " is ", n, ": needs at least ", std::uint64_t(n) * min_item_bytes, " bytes, ",
                     left(), " left");
        return std::uint32_t(n);
    }

    std::span<const std::uint8_t> bytes(std::uint64_t n, const char* what) {
        need(n, what);
        auto s = file_.subspan(pos_, std::size_t(n));
        pos_ += std::size_t(n);
        return s;
    }
    void skip(std::uint64_t n, const char* what) { bytes(n, what); }

    // STRING: int32 length, then that many bytes (no terminator).
    std::string_view string(const char* what) {
        auto n = count(what, 1);
        auto b = bytes(n, what);
        return {reinterpret_cast<const char*>(b.data()), b.size()};
    }

private:
    std::span<const std::uint8_t> file_;
    std::size_t pos_;
    std::size_t end_;
    std::string_view name_;
    std::string chunk_;
};

// Parses a whole string as one integer or float; returns false on junk, overflow or
// (for floats) a non-finite value. Dictionary values in .vox are text.
template <class T>
bool vox_parse_number(std::string_view s, T& out) {
    // from_chars does not skip leading blanks; MagicaVoxel writes none, but be kind.
    while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
    while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
    if (!s.empty() && s.front() == '+') s.remove_prefix(1);
    T v{};
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (ec != std::errc() || end != s.data() + s.size() || s.empty()) return false;
    if constexpr (std::is_floating_point_v<T>)
        if (!std::isfinite(v)) return false;
    out = v;
    return true;
}

}  // namespace voxray::io
