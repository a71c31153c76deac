// MagicaVoxel .vox reader: versions 150 and 200, multi-model files (PACK), the scene
// graph (nTRN / nGRP / nSHP with translation, rotation, nested groups, instancing and
// animation frames), the palette (RGBA, else MagicaVoxel's default) and materials (MATL).
//
//   auto model = voxray::io::load_vox("castle.vox");            // composed scene
//   auto scene = voxray::io::load_vox_scene("castle.vox", {.frame = 3});
//   scene.stats.instances, scene.stats.placed_bounds, ...
//
// The model keeps the file's axes: x, y, z with **Z up**, and coordinates may be negative
// (MagicaVoxel centres scenes on the origin). Where a file places models over each
// other, the voxel set keeps each position once (the later write wins), so
// voxel_count() can be below stats.placed_voxels and bounds() is the tight box of the
// solid voxels, while stats.placed_bounds is the union of the placed models' SIZE boxes.
//
// Any malformed input throws voxray::error naming the file, the byte offset, the chunk
// and the bad value; nothing is read outside the given bytes. The pieces:
//   vox_cursor.hpp           checked reads
//   vox_chunks.hpp           chunk parsing and the format's limits
//   vox_scene.hpp            scene graph composition, vox_options, vox_scene_stats
//   vox_rotation.hpp         the packed rotation byte
//   vox_default_palette.hpp  the palette used when the file has none
#pragma once
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/io/vox_chunks.hpp"
#include "voxray/io/vox_default_palette.hpp"
#include "voxray/io/vox_scene.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::io {

struct vox_scene {
    voxel_model model;
    vox_scene_stats stats;
};

// Parses and composes a .vox file held in memory; `name_for_errors` prefixes messages.
inline vox_scene read_vox_scene(std::span<const std::uint8_t> bytes, std::string_view name_for_errors,
                                const vox_options& options = {}) {
    vox_file file = parse_vox_chunks(bytes, name_for_errors);
    vox_scene scene;
    auto& s = scene.stats;
    s.version = file.version;
    s.models = file.models.size();
    s.nodes = file.nodes.size();
    s.has_palette = file.palette.has_value();
    s.material_chunks = file.material_chunks;

    auto& pal = scene.model.palette();
    const auto& colours = file.palette ? *file.palette : vox_default_palette;
    for (int i = 0; i < palette::size; ++i) {
        pal[std::uint8_t(i)].colour = colours[i];
        if (file.materials[i]) pal[std::uint8_t(i)].mat = *file.materials[i];
    }
    compose_vox(file, options, name_for_errors, scene.model, s);
    return scene;
}

inline voxel_model read_vox(std::span<const std::uint8_t> bytes, std::string_view name_for_errors,
                            const vox_options& options = {}) {
    return std::move(read_vox_scene(bytes, name_for_errors, options).model);
}

// The whole file as bytes; throws voxray::error when it cannot be read.
inline std::vector<std::uint8_t> read_file_bytes(const std::filesystem::path& path) {
    std::error_code ec;
    auto size = std::filesystem::file_size(path, ec);
    if (ec) fail(path.string(), ": cannot read: ", ec.message());
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path.string(), ": cannot open");
    std::vector<std::uint8_t> bytes(size);
    if (size && !in.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))
        fail(path.string(), ": read failed after ", in.gcount(), " of ", size, " bytes");
    return bytes;
}

inline vox_scene load_vox_scene(const std::filesystem::path& path, const vox_options& options = {}) {
    auto bytes = read_file_bytes(path);
    return read_vox_scene(bytes, path.string(), options);
}

inline voxel_model load_vox(const std::filesystem::path& path, const vox_options& options = {}) {
    return std::move(load_vox_scene(path, options).model);
}

}  // namespace voxray::io
