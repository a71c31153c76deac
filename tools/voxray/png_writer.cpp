// The one translation unit that compiles stb_image_write.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include "png_writer.hpp"
#include "voxray/core/error.hpp"

namespace voxray::tool {

void write_png(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb) {
    if (rgb.size() != std::size_t(width) * std::size_t(height) * 3)
        fail("write_png: ", rgb.size(), " bytes for a ", width, " x ", height, " RGB image");
    if (!stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3)) fail("cannot write PNG ", path);
}

}  // namespace voxray::tool
