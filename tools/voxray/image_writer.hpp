// The tool's images through stb_image_write, in the format the file name asks for:
// .png (zlib-compressed rows), .jpg/.jpeg (quality 92), .bmp or .tga. The bytes are
// encoded in memory and written as one checked file (output.hpp), so a full disk is an
// error, not an empty image.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace voxray::tool {

// Fails, naming the option and the formats known, unless `path` ends in one of them;
// checked before any scene loads.
void require_image_path(const std::string& path, const std::string& option);

// Writes 8-bit RGB pixels, rows top to bottom; throws voxray::error when it cannot.
void write_image(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb);

}  // namespace voxray::tool
