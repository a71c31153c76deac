// PNG output of the tool through stb_image_write (zlib-compressed rows).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace voxray::tool {

// Writes 8-bit RGB pixels, rows top to bottom; throws voxray::error when it cannot.
void write_png(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb);

}  // namespace voxray::tool
