// Chunk level of the MagicaVoxel .vox reader: bytes -> vox_file (models, scene graph
// nodes, palette, materials), with every size checked before it is used.
//
// File layout (all integers little-endian int32):
//
//   "VOX " version                     version 150 or 200
//   MAIN  N=0  M                       M = bytes of all child chunks below
//     +-- chunk: id[4] N M content[N] children[M]
//     |     PACK  numModels            optional, informational
//     |     SIZE  x y z                then XYZI: one model
//     |     XYZI  n, n x (x y z i)     bytes; i = palette index 1..255
//     |     RGBA  256 x (r g b a)      entry k is palette index k+1
//     |     MATL  id DICT              material of palette index id
//     |     nTRN  id DICT child reserved layer numFrames numFrames x DICT(_t _r _f)
//     |     nGRP  id DICT n n x childId
//     |     nSHP  id DICT n n x (modelId DICT(_f))
//     |     LAYR  id DICT reserved
//     +--   anything else (rOBJ rCAM NOTE IMAP MATT ...) is skipped
//   STRING = int32 length + bytes; DICT = int32 count + count x (STRING key, STRING value)
//
// Robustness rules (each violation throws voxray::error with file, byte offset, chunk
// id and the bad value):
//   - Truncation: a chunk cut short is an error. A file cut exactly at a chunk boundary
//     holds fewer bytes than MAIN declares: an error, except in PACK-era files (rock.vox
//     declares 0x7fffff bytes, a placeholder): PACK counts exactly the models read, there
//     is no scene graph, and the palette (RGBA, written after the models) is there.
//     PACK's count must always match the models read.
//   - SIZE must be 1..vox_max_model_size per axis; XYZI must fit its chunk; a voxel
//     outside its model's SIZE is rejected (the file is corrupt, and guessing where the
//     voxel belongs would hide that). Voxels with palette index 0 are skipped: 0 means
//     empty.
//   - Counts (dictionary entries, children, frames, models) are checked against the bytes
//     left before anything is allocated for them.
#pragma once
#include <algorithm>
#include <cmath>
#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "voxray/io/vox_cursor.hpp"
#include "voxray/io/vox_rotation.hpp"
#include "voxray/model/palette.hpp"

namespace voxray::io {

// MagicaVoxel itself stops at 256 per axis; other tools write bigger models.
inline constexpr int vox_max_model_size = 2048;

struct vox_model_data {
    glm::ivec3 size{0};
    std::vector<std::array<std::uint8_t, 4>> voxels;  // x y z index, index != 0
    std::size_t offset = 0;                          // of its SIZE chunk, for messages
};

// One keyframe of a transform node.
struct vox_frame {
    int key = 0;                  // _f, else its position in the list
    glm::i64vec3 translation{0};  // _t
    vox_rotation rotation;        // _r
};

struct vox_node {
    enum class kind : std::uint8_t { transform, group, shape };
    kind type = kind::transform;
    std::int32_t id = 0;
    std::size_t offset = 0;  // of its chunk, for messages
    bool hidden = false;     // _hidden in the node's attributes
    std::int32_t layer = -1;                                  // transform only
    std::int32_t child = -1;                                  // transform only
    std::vector<vox_frame> frames;                            // transform only
    std::vector<std::int32_t> children;                       // group only
    std::vector<std::pair<int, std::int32_t>> models;         // shape only: (frame key, model id)
};

struct vox_file {
    int version = 0;
    int pack_models = -1;  // PACK's count, -1 when absent
    std::vector<vox_model_data> models;
    std::vector<vox_node> nodes;  // in file order
    std::unordered_map<std::int32_t, bool> hidden_layers;
    std::optional<std::array<rgba, 256>> palette;  // indexed by palette index
    std::array<std::optional<material>, 256> materials;
    int material_chunks = 0;
};

namespace detail {

using vox_dict = std::vector<std::pair<std::string_view, std::string_view>>;

inline vox_dict read_dict(vox_cursor& c) {
    auto n = c.count("dictionary entry count", 8);  // two empty strings at least
    vox_dict d;
    d.reserve(n);
    for (std::uint32_t i = 0; i < n; ++i) {
        auto key = c.string("dictionary key");
        auto value = c.string("dictionary value");
        d.emplace_back(key, value);
    }
    return d;
}

inline const std::string_view* find(const vox_dict& d, std::string_view key) {
    for (auto& [k, v] : d)
        if (k == key) return &v;
    return nullptr;
}

template <class T>
T dict_number(const vox_cursor& c, std::size_t at, const vox_dict& d, std::string_view key, T fallback) {
    auto* v = find(d, key);
    if (!v) return fallback;
    T out{};
    if (!vox_parse_number(*v, out)) c.error_at(at, "value of ", key, " is not a valid number: ", vox_quote(*v));
    return out;
}

inline bool dict_flag(const vox_cursor& c, std::size_t at, const vox_dict& d, std::string_view key) {
    return dict_number<int>(c, at, d, key, 0) != 0;
}

// _t: three integers separated by single spaces, e.g. "-11 -13 3".
inline glm::i64vec3 parse_translation(const vox_cursor& c, std::size_t at, std::string_view s) {
    glm::i64vec3 t{0};
    std::string_view rest = s;
    for (int i = 0; i < 3; ++i) {
        while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
        auto end = std::min(rest.find(' '), rest.size());
        std::int32_t v = 0;
        if (!vox_parse_number(rest.substr(0, end), v))
            c.error_at(at, "translation _t is not three integers: ", vox_quote(s));
        t[i] = v;
        rest.remove_prefix(end);
    }
    while (!rest.empty() && rest.front() == ' ') rest.remove_prefix(1);
    if (!rest.empty()) c.error_at(at, "translation _t is not three integers: ", vox_quote(s));
    return t;
}

inline material_kind parse_material_kind(std::string_view t) {
    if (t == "_metal") return material_kind::metal;
    if (t == "_glass") return material_kind::glass;
    if (t == "_emit") return material_kind::emit;
    if (t == "_blend") return material_kind::blend;
    if (t == "_media") return material_kind::media;
    if (t == "_cloud") return material_kind::cloud;
    return material_kind::diffuse;  // "_diffuse", absent, or a type newer than this reader
}

// MATL's dictionary -> material. Keys: _type _rough _metal _ior (stored as IOR - 1)
// _ri (the IOR itself, newer files) _emit _flux (emission power, exponential) _trans
// (_alpha in older files). Keys this reader does not model (_d density, _g phase,
// _media type, _sp, _att, _ldr ...) are ignored.
inline material parse_material(const vox_cursor& c, std::size_t at, const vox_dict& d) {
    material m;
    if (auto* t = find(d, "_type")) m.kind = parse_material_kind(*t);
    m.roughness = dict_number(c, at, d, "_rough", m.roughness);
    m.metalness = dict_number(c, at, d, "_metal", m.metalness);
    m.ior = 1.0f + dict_number(c, at, d, "_ior", m.ior - 1.0f);
    m.ior = dict_number(c, at, d, "_ri", m.ior);
    float emit = dict_number(c, at, d, "_emit", 0.0f);
    float flux = dict_number(c, at, d, "_flux", 0.0f);
    if (flux < -8.0f || flux > 8.0f) c.error_at(at, "emission power _flux is ", flux, ", outside -8..8");
    m.emission = emit * float(std::pow(10.0, double(flux)));
    m.transparency = dict_number(c, at, d, "_alpha", m.transparency);
    m.transparency = dict_number(c, at, d, "_trans", m.transparency);
    // Out-of-range numbers (_rough=-5, _ior=1e38) are errors, not materials a shader
    // would turn into NaN or black.
    if (std::string why = material_range_error(m); !why.empty()) c.error_at(at, "MATL material ", why);
    return m;
}

inline void read_size(vox_cursor& c, std::size_t chunk_at, vox_file& f, std::optional<vox_model_data>& pending) {
    if (pending)
        c.error_at(chunk_at, "second SIZE chunk before the XYZI of the SIZE at byte ", pending->offset);
    vox_model_data m;
    m.offset = chunk_at;
    for (int i = 0; i < 3; ++i) m.size[i] = c.i32("model size");
    for (int i = 0; i < 3; ++i)
        if (m.size[i] < 1 || m.size[i] > vox_max_model_size)
            c.error_at(chunk_at, "model size ", m.size.x, " x ", m.size.y, " x ", m.size.z, " is outside 1..",
                       vox_max_model_size, " per axis (model ", f.models.size(), ")");
    pending = std::move(m);
}

inline void read_xyzi(vox_cursor& c, std::size_t chunk_at, vox_file& f, std::optional<vox_model_data>& pending) {
    if (!pending) c.error_at(chunk_at, "XYZI chunk without a SIZE chunk before it");
    auto count = c.count("voxel count", 4);
    auto data = c.bytes(std::uint64_t(count) * 4, "voxels");
    auto& m = *pending;
    m.voxels.reserve(count);
    for (std::uint32_t i = 0; i < count; ++i) {
        std::array<std::uint8_t, 4> v{data[4 * i], data[4 * i + 1], data[4 * i + 2], data[4 * i + 3]};
        if (v[0] >= m.size.x || v[1] >= m.size.y || v[2] >= m.size.z)
            c.error_at(chunk_at + 16 + 4 * std::size_t(i), "voxel ", i, " at (", int(v[0]), ", ", int(v[1]), ", ",
                       int(v[2]), ") is outside its model's size ", m.size.x, " x ", m.size.y, " x ", m.size.z);
        if (v[3] != 0) m.voxels.push_back(v);
    }
    f.models.push_back(std::move(m));
    pending.reset();
}

inline void read_rgba(vox_cursor& c, vox_file& f) {
    auto data = c.bytes(256 * 4, "palette");
    std::array<rgba, 256> p{};
    // Entry k describes palette index k + 1; the last entry would be index 0 (empty).
    for (int k = 0; k < 255; ++k)
        p[k + 1] = {data[4 * k], data[4 * k + 1], data[4 * k + 2], data[4 * k + 3]};
    f.palette = p;
}

inline void read_matl(vox_cursor& c, std::size_t chunk_at, vox_file& f) {
    auto id = c.i32("material id");
    // MagicaVoxel numbers materials like palette indices, 1..256 (256 being index 0).
    if (id < 0 || id > 256) c.error_at(chunk_at, "material id ", id, " is outside 0..256");
    auto d = read_dict(c);
    auto m = parse_material(c, chunk_at, d);
    ++f.material_chunks;
    if (id >= 1 && id <= 255) f.materials[id] = m;
}

inline vox_node read_node(vox_cursor& c, std::size_t chunk_at, vox_node::kind type) {
    vox_node n;
    n.type = type;
    n.offset = chunk_at;
    n.id = c.i32("node id");
    if (n.id < 0) c.error_at(chunk_at, "node id ", n.id, " is negative");
    auto attributes = read_dict(c);
    n.hidden = dict_flag(c, chunk_at, attributes, "_hidden");
    switch (type) {
    case vox_node::kind::transform: {
        n.child = c.i32("child node id");
        c.i32("reserved id");
        n.layer = c.i32("layer id");
        auto frames = c.count("frame count", 4);
        n.frames.reserve(frames);
        for (std::uint32_t i = 0; i < frames; ++i) {
            auto at = c.offset();
            auto d = read_dict(c);
            vox_frame fr;
            fr.key = dict_number(c, at, d, "_f", int(i));
            if (auto* t = find(d, "_t")) fr.translation = parse_translation(c, at, *t);
            if (auto* r = find(d, "_r")) {
                int packed = -1;
                auto rot = vox_parse_number(*r, packed) ? vox_rotation::from_byte(packed) : std::nullopt;
                if (!rot) c.error_at(at, "rotation _r ", vox_quote(*r), " is not a valid packed rotation");
                fr.rotation = *rot;
            }
            n.frames.push_back(fr);
        }
        break;
    }
    case vox_node::kind::group: {
        auto count = c.count("child count", 4);
        n.children.reserve(count);
        for (std::uint32_t i = 0; i < count; ++i) n.children.push_back(c.i32("child node id"));
        break;
    }
    case vox_node::kind::shape: {
        auto count = c.count("model count", 8);
        n.models.reserve(count);
        for (std::uint32_t i = 0; i < count; ++i) {
            auto at = c.offset();
            auto model = c.i32("model id");
            auto d = read_dict(c);
            n.models.emplace_back(dict_number(c, at, d, "_f", int(i)), model);
        }
        break;
    }
    }
    return n;
}

inline bool is_id(std::span<const std::uint8_t, 4> id, const char (&name)[5]) {
    return std::equal(id.begin(), id.end(), name);
}

}  // namespace detail

// Reads every chunk of a .vox file. Does not compose the scene (see vox_scene.hpp).
inline vox_file parse_vox_chunks(std::span<const std::uint8_t> bytes, std::string_view name) {
    using namespace detail;
    vox_file f;
    vox_cursor header(bytes, 0, bytes.size(), name);
    auto magic = header.bytes(4, "file header");
    if (!std::equal(magic.begin(), magic.end(), "VOX "))
        header.error_at(0, "not a MagicaVoxel file: it starts with '", vox_chunk_name(magic.first<4>()),
                        "' instead of 'VOX '");
    f.version = header.i32("version");
    if (f.version != 150 && f.version != 200)
        header.error_at(4, "unsupported .vox version ", f.version, " (this reader knows 150 and 200)");

    auto main_at = header.offset();
    auto main_id = header.bytes(4, "MAIN chunk header").first<4>();
    if (!is_id(main_id, "MAIN"))
        header.error_at(main_at, "first chunk is '", vox_chunk_name(main_id), "', expected 'MAIN'");
    auto main_content = header.count("MAIN content size", 1);
    auto main_children = header.i32("MAIN children size");
    if (main_children < 0) header.error_at(main_at, "MAIN children size ", main_children, " is negative");
    header.skip(main_content, "MAIN content");
    // Clamp: rock.vox declares 0x7fffff bytes of children in a 360 KB file (checked below).
    const std::size_t available = header.left();
    std::size_t end = header.offset() + std::min<std::size_t>(std::size_t(main_children), header.left());

    std::optional<vox_model_data> pending;
    std::unordered_map<std::int32_t, std::size_t> node_offsets;
    vox_cursor walk(bytes, header.offset(), end, name);
    while (walk.left() > 0) {
        auto at = walk.offset();
        auto id = walk.bytes(4, "chunk header (12 bytes)").first<4>();
        auto chunk_name = vox_chunk_name(id);
        vox_cursor sizes(bytes, walk.offset(), end, name, chunk_name);
        auto content = sizes.count("content size", 1);
        auto children = sizes.i32("children size");
        if (children < 0) sizes.error_at(at + 8, "children size ", children, " is negative");
        if (std::uint64_t(children) > sizes.left() - content)
            sizes.error_at(at + 8, "children size ", children, " goes past the end of the data (",
                           sizes.left() - content, " bytes after the content)");
        vox_cursor c(bytes, sizes.offset(), sizes.offset() + content, name, chunk_name);
        walk = vox_cursor(bytes, sizes.offset() + content + std::size_t(children), end, name);

        if (is_id(id, "SIZE")) read_size(c, at, f, pending);
        else if (is_id(id, "XYZI")) read_xyzi(c, at, f, pending);
        else if (is_id(id, "RGBA")) read_rgba(c, f);
        else if (is_id(id, "MATL")) read_matl(c, at, f);
        else if (is_id(id, "PACK")) {
            auto n = c.i32("model count");
            if (n < 0) c.error_at(at, "PACK model count ", n, " is negative");
            f.pack_models = n;
        } else if (is_id(id, "LAYR")) {
            auto layer = c.i32("layer id");
            auto d = read_dict(c);
            f.hidden_layers[layer] = dict_flag(c, at, d, "_hidden");
        } else if (is_id(id, "nTRN") || is_id(id, "nGRP") || is_id(id, "nSHP")) {
            auto type = is_id(id, "nTRN")   ? vox_node::kind::transform
                        : is_id(id, "nGRP") ? vox_node::kind::group
                                            : vox_node::kind::shape;
            auto node = read_node(c, at, type);
            auto [it, added] = node_offsets.emplace(node.id, at);
            if (!added) c.error_at(at, "node id ", node.id, " already used by the chunk at byte ", it->second);
            f.nodes.push_back(std::move(node));
        }
        // Other chunks (rOBJ rCAM NOTE IMAP MATT ...) carry nothing we need.
    }
    if (pending) fail(name, ": byte ", pending->offset, " in chunk 'SIZE': model has no XYZI chunk after it");
    bool pack_matches = f.pack_models >= 0 && std::size_t(f.pack_models) == f.models.size();
    bool pack_era_complete = pack_matches && f.nodes.empty() && f.palette.has_value();
    if (f.pack_models >= 0 && !pack_matches)
        fail(name, ": PACK declares ", f.pack_models, " models but the file holds ", f.models.size(),
             " (truncated or corrupt)");
    if (std::size_t(main_children) > available && !pack_era_complete)
        fail(name, ": byte ", main_at + 8, ": MAIN declares ", main_children,
             " bytes of chunks but the file holds ", available, " after MAIN's header (truncated)");
    return f;
}

}  // namespace voxray::io
