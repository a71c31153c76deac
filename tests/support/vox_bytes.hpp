// Building MagicaVoxel .vox files byte by byte, for tests: chunks, the scene graph's
// nodes and whole files. Nothing here checks what it writes, so tests can build
// malformed files as easily as well-formed ones.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace voxray::test::vox_bytes {

using bytes = std::vector<std::uint8_t>;

inline void put_u32(bytes& b, std::uint32_t v) {
    for (int i = 0; i < 4; ++i) b.push_back(std::uint8_t(v >> (8 * i)));
}
inline void put_str(bytes& b, const std::string& s) {
    put_u32(b, std::uint32_t(s.size()));
    b.insert(b.end(), s.begin(), s.end());
}
using dict = std::vector<std::pair<std::string, std::string>>;
inline void put_dict(bytes& b, const dict& d) {
    put_u32(b, std::uint32_t(d.size()));
    for (auto& [k, v] : d) put_str(b, k), put_str(b, v);
}

inline bytes chunk(const char* id, const bytes& content, std::uint32_t children = 0) {
    bytes b(id, id + 4);
    put_u32(b, std::uint32_t(content.size()));
    put_u32(b, children);
    b.insert(b.end(), content.begin(), content.end());
    return b;
}

inline bytes vox(const std::vector<bytes>& chunks, int version = 150, std::int64_t main_children = -1) {
    bytes body;
    for (auto& c : chunks) body.insert(body.end(), c.begin(), c.end());
    bytes b{'V', 'O', 'X', ' '};
    put_u32(b, std::uint32_t(version));
    b.insert(b.end(), {'M', 'A', 'I', 'N'});
    put_u32(b, 0);
    put_u32(b, main_children < 0 ? std::uint32_t(body.size()) : std::uint32_t(main_children));
    b.insert(b.end(), body.begin(), body.end());
    return b;
}

inline bytes size_chunk(int x, int y, int z) {
    bytes c;
    put_u32(c, std::uint32_t(x)), put_u32(c, std::uint32_t(y)), put_u32(c, std::uint32_t(z));
    return chunk("SIZE", c);
}
inline bytes xyzi_chunk(const std::vector<std::array<std::uint8_t, 4>>& voxels) {
    bytes c;
    put_u32(c, std::uint32_t(voxels.size()));
    for (auto& v : voxels) c.insert(c.end(), v.begin(), v.end());
    return chunk("XYZI", c);
}
inline bytes ntrn(int id, int child, const dict& frame, const dict& attributes = {}, int layer = 0) {
    bytes c;
    put_u32(c, std::uint32_t(id));
    put_dict(c, attributes);
    put_u32(c, std::uint32_t(child)), put_u32(c, 0xffffffffu), put_u32(c, std::uint32_t(layer));
    put_u32(c, 1);
    put_dict(c, frame);
    return chunk("nTRN", c);
}
inline bytes ngrp(int id, const std::vector<int>& children) {
    bytes c;
    put_u32(c, std::uint32_t(id));
    put_dict(c, {});
    put_u32(c, std::uint32_t(children.size()));
    for (int ch : children) put_u32(c, std::uint32_t(ch));
    return chunk("nGRP", c);
}
inline bytes nshp(int id, const std::vector<std::pair<int, dict>>& models) {
    bytes c;
    put_u32(c, std::uint32_t(id));
    put_dict(c, {});
    put_u32(c, std::uint32_t(models.size()));
    for (auto& [m, d] : models) put_u32(c, std::uint32_t(m)), put_dict(c, d);
    return chunk("nSHP", c);
}

}  // namespace voxray::test::vox_bytes
