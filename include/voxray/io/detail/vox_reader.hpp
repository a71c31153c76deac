// The .vox reader's definitions (declared in io/vox_reader.hpp).
#pragma once
#include <filesystem>
#include <fstream>
#include <span>
#include <string_view>
#include <system_error>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/io/vox_chunks.hpp"
#include "voxray/io/vox_default_palette.hpp"
#include "voxray/io/vox_reader.hpp"
#include "voxray/io/vox_scene.hpp"

namespace voxray::io {

VOXRAY_HOST_INLINE vox_scene read_vox_scene(std::span<const std::uint8_t> bytes, std::string_view name_for_errors,
                                            const vox_options& options) {
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

VOXRAY_HOST_INLINE voxel_model read_vox(std::span<const std::uint8_t> bytes, std::string_view name_for_errors,
                                        const vox_options& options) {
    return std::move(read_vox_scene(bytes, name_for_errors, options).model);
}

VOXRAY_HOST_INLINE std::vector<std::uint8_t> read_file_bytes(const std::filesystem::path& path) {
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

VOXRAY_HOST_INLINE vox_scene load_vox_scene(const std::filesystem::path& path, const vox_options& options) {
    auto bytes = read_file_bytes(path);
    return read_vox_scene(bytes, path.string(), options);
}

VOXRAY_HOST_INLINE voxel_model load_vox(const std::filesystem::path& path, const vox_options& options) {
    return std::move(load_vox_scene(path, options).model);
}

}  // namespace voxray::io
