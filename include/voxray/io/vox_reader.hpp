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
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "voxray/core/host_code.hpp"
#include "voxray/io/vox_scene.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::io {

struct vox_scene {
    voxel_model model;
    vox_scene_stats stats;
};

// Parses and composes a .vox file held in memory; `name_for_errors` prefixes messages.
VOXRAY_HOST_INLINE vox_scene read_vox_scene(std::span<const std::uint8_t> bytes, std::string_view name_for_errors,
                                            const vox_options& options = {});
VOXRAY_HOST_INLINE voxel_model read_vox(std::span<const std::uint8_t> bytes, std::string_view name_for_errors,
                                        const vox_options& options = {});
// The whole file as bytes; throws voxray::error when it cannot be read.
VOXRAY_HOST_INLINE std::vector<std::uint8_t> read_file_bytes(const std::filesystem::path& path);
VOXRAY_HOST_INLINE vox_scene load_vox_scene(const std::filesystem::path& path, const vox_options& options = {});
VOXRAY_HOST_INLINE voxel_model load_vox(const std::filesystem::path& path, const vox_options& options = {});

}  // namespace voxray::io

// The definitions: here, or compiled once in voxray::kernels (core/host_code.hpp).
#if VOXRAY_HOST_DEFINITIONS
#include "voxray/io/detail/vox_reader.hpp"
#endif
