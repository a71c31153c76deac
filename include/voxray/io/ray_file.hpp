// The .vxrays file: a fixed set of rays, so that other libraries can be fed the very same
// rays a voxray benchmark traced (`voxray bench --write-rays DIR`, `--ray-file FILE`).
//
//   offset  size  field
//   0       8     magic "VXRAYS01"
//   8       4     uint32 ray size in bytes: 32
//   12      4     uint32 reserved, 0
//   16      8     uint64 ray count N
//   24      32*N  rays, each 8 float32: origin x y z, tmin, direction x y z, tmax
//
// All little-endian IEEE-754; one unit is one voxel edge (world voxel coordinates, voxel
// (x, y, z) covers [x, x+1) x [y, y+1) x [z, z+1)). tmax may be +inf; a ray with
// tmin > tmax is a placeholder that misses (e.g. a bounce from a pixel that hit nothing).
// The ray layout is voxray::ray's, so the rays are read straight into place.
#pragma once
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <span>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/core/ray.hpp"

namespace voxray::io {

inline constexpr char ray_file_magic[8] = {'V', 'X', 'R', 'A', 'Y', 'S', '0', '1'};
inline constexpr std::uint64_t ray_file_limit = std::uint64_t(1) << 30;  // rays; 32 GiB

static_assert(std::endian::native == std::endian::little, "the .vxrays reader assumes a little-endian host");

inline void write_rays(const std::filesystem::path& path, std::span<const ray> rays) {
    std::ofstream out(path, std::ios::binary);
    if (!out) fail("cannot open ", path.string(), " for writing");
    std::uint32_t sizes[2] = {sizeof(ray), 0};
    std::uint64_t count = rays.size();
    out.write(ray_file_magic, 8);
    out.write(reinterpret_cast<const char*>(sizes), 8);
    out.write(reinterpret_cast<const char*>(&count), 8);
    out.write(reinterpret_cast<const char*>(rays.data()), std::streamsize(rays.size_bytes()));
    out.close();  // a full disk shows when the buffer is flushed
    if (!out) fail("could not write ", rays.size(), " rays to ", path.string());
}

// The ray count of a .vxrays file, its header checked against the file's size: what a
// caller checks its memory against before read_rays allocates. Only a regular file is
// opened (a FIFO would block the open until some writer came).
inline std::uint64_t ray_file_count(const std::filesystem::path& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) fail("ray file ", path.string(), ": not a regular file");
    std::ifstream in(path, std::ios::binary);
    if (!in) fail("ray file ", path.string(), " cannot be opened");
    char magic[8];
    std::uint32_t sizes[2];
    std::uint64_t count = 0;
    in.read(magic, 8);
    in.read(reinterpret_cast<char*>(sizes), 8);
    in.read(reinterpret_cast<char*>(&count), 8);
    if (!in || std::memcmp(magic, ray_file_magic, 8) != 0) fail("ray file ", path.string(), ": not a .vxrays file (magic VXRAYS01)");
    if (sizes[0] != sizeof(ray)) fail("ray file ", path.string(), ": ray size ", sizes[0], ", expected ", sizeof(ray));
    if (sizes[1] != 0) fail("ray file ", path.string(), ": reserved word at offset 12 is ", sizes[1], ", expected 0");
    if (count > ray_file_limit) fail("ray file ", path.string(), ": ", count, " rays, above the limit of ", ray_file_limit);
    auto expected = 24 + count * sizeof(ray);
    auto actual = std::filesystem::file_size(path);
    if (actual != expected)
        fail("ray file ", path.string(), ": ", actual, " bytes, but a header for ", count, " rays means ", expected);
    return count;
}

inline std::vector<ray> read_rays(const std::filesystem::path& path) {
    std::uint64_t count = ray_file_count(path);
    std::ifstream in(path, std::ios::binary);
    in.seekg(24);
    std::vector<ray> rays(count);
    in.read(reinterpret_cast<char*>(rays.data()), std::streamsize(count * sizeof(ray)));
    if (!in) fail("ray file ", path.string(), ": could not read ", count, " rays");
    return rays;
}

}  // namespace voxray::io
