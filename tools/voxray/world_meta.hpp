// voxray-world.json: the shading hints world-build leaves beside a world's manifest (the
// scene's up axis and palette). Read as untrusted input: only a regular file of at most
// 1 MiB (a FIFO would hang the read), valid JSON, an integer up axis in {0, 1, 2}, a
// palette of at most 256 unsigned 32-bit RGBA words; every failure names the file and
// the field. A world without the file (built through the library) is Z up and grey.
#pragma once
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <nlohmann/json.hpp>

#include "voxray/core/error.hpp"
#include "voxray/model/palette.hpp"

namespace voxray::tool {

inline constexpr const char* world_meta_file = "voxray-world.json";
inline constexpr std::uint64_t world_meta_limit = std::uint64_t(1) << 20;

struct world_meta {
    int up_axis = 2;
    palette colours;
};

inline world_meta read_world_meta(const std::filesystem::path& dir) {
    world_meta meta;
    auto path = dir / world_meta_file;
    std::string name = path.string();
    std::error_code ec;
    auto status = std::filesystem::status(path, ec);
    if (status.type() == std::filesystem::file_type::not_found) return meta;
    if (status.type() != std::filesystem::file_type::regular) fail(name, ": not a regular file");
    auto size = std::filesystem::file_size(path, ec);
    if (ec || size > world_meta_limit) fail(name, ": ", size, " bytes, more than the limit of ", world_meta_limit);
    std::ifstream in(path, std::ios::binary);
    std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
    if (in.bad() || text.size() != size) fail(name, ": read failed (", text.size(), " of ", size, " bytes)");
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception& e) {
        fail(name, ": not valid JSON (", e.what(), ")");
    }
    if (!j.is_object()) fail(name, ": not a JSON object");
    if (j.contains("up_axis")) {
        const auto& a = j["up_axis"];
        if (!a.is_number_integer() || a.get<std::int64_t>() < 0 || a.get<std::int64_t>() > 2)
            fail(name, ": up_axis ", a.dump(), " is not 0, 1 or 2");
        meta.up_axis = a.get<int>();
    }
    if (j.contains("palette")) {
        const auto& p = j["palette"];
        if (!p.is_array() || p.size() > 256) fail(name, ": palette is not an array of at most 256 colours");
        for (std::size_t i = 0; i < p.size(); ++i) {
            if (!p[i].is_number_unsigned() || p[i].get<std::uint64_t>() > 0xffffffffu)
                fail(name, ": palette[", i, "] ", p[i].dump(), " is not an RGBA word (an unsigned 32-bit integer)");
            auto c = p[i].get<std::uint32_t>();
            meta.colours[std::uint8_t(i)].colour = rgba{std::uint8_t(c), std::uint8_t(c >> 8), std::uint8_t(c >> 16), 255};
        }
    }
    return meta;
}

}  // namespace voxray::tool
