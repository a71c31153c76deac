// The one translation unit that compiles stb_image_write.
#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cctype>
#include <filesystem>

#include "image_writer.hpp"
#include "output.hpp"
#include "voxray/core/error.hpp"

namespace voxray::tool {

namespace {

enum class image_format { png, jpg, bmp, tga, unknown };

image_format format_of(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    if (ext == ".png") return image_format::png;
    if (ext == ".jpg" || ext == ".jpeg") return image_format::jpg;
    if (ext == ".bmp") return image_format::bmp;
    if (ext == ".tga") return image_format::tga;
    return image_format::unknown;
}

void append(void* context, void* data, int size) {
    auto* bytes = static_cast<std::string*>(context);
    bytes->append(static_cast<const char*>(data), std::size_t(size));
}

}  // namespace

void require_image_path(const std::string& path, const std::string& option) {
    if (format_of(path) == image_format::unknown)
        fail(option, " ", path, ": unknown image format '", std::filesystem::path(path).extension().string(),
             "' (known: .png, .jpg, .jpeg, .bmp, .tga)");
}

void write_image(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb) {
    if (rgb.size() != std::size_t(width) * std::size_t(height) * 3)
        fail("write_image: ", rgb.size(), " bytes for a ", width, " x ", height, " RGB image");
    std::string bytes;
    int ok = 0;
    switch (format_of(path)) {
        case image_format::png: ok = stbi_write_png_to_func(append, &bytes, width, height, 3, rgb.data(), width * 3); break;
        case image_format::jpg: ok = stbi_write_jpg_to_func(append, &bytes, width, height, 3, rgb.data(), 92); break;
        case image_format::bmp: ok = stbi_write_bmp_to_func(append, &bytes, width, height, 3, rgb.data()); break;
        case image_format::tga: ok = stbi_write_tga_to_func(append, &bytes, width, height, 3, rgb.data()); break;
        case image_format::unknown: require_image_path(path, "image"); break;
    }
    if (!ok) fail("image ", path, ": encoding failed");
    output_file out(path, "image");
    out.stream().write(bytes.data(), std::streamsize(bytes.size()));
    out.finish();
}

}  // namespace voxray::tool
