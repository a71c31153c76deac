// Helpers shared by the mesh tests: temporary files, small meshes, model hashes.
#pragma once
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <unistd.h>

#include <gtest/gtest.h>

#include "voxray/io/mesh.hpp"
#include "voxray/model/voxel_model.hpp"

namespace voxray::test {

// A fresh folder per test, removed at the end.
class temp_dir {
public:
    temp_dir() {
        auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        std::string name = std::string("voxray_") + (info ? info->test_suite_name() : "t") + "_" +
                           (info ? info->name() : "t") + "_" + std::to_string(::getpid());
        path_ = std::filesystem::temp_directory_path() / name;
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~temp_dir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    std::filesystem::path write(const std::string& file, std::string_view bytes) const {
        auto p = path_ / file;
        std::ofstream(p, std::ios::binary).write(bytes.data(), std::streamsize(bytes.size()));
        return p;
    }
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

// Axis-aligned box [lo, hi]^3 as 12 outward-facing triangles appended to `m`.
inline void add_box(io::triangle_mesh& m, glm::dvec3 lo, glm::dvec3 hi, std::uint32_t group = 0) {
    auto base = std::uint32_t(m.positions.size());
    for (int i = 0; i < 8; ++i) m.positions.push_back({i & 1 ? hi.x : lo.x, i & 2 ? hi.y : lo.y, i & 4 ? hi.z : lo.z});
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (auto& q : quads) {
        m.triangles.push_back({base + q[0], base + q[1], base + q[2]});
        m.triangles.push_back({base + q[0], base + q[2], base + q[3]});
        m.groups.push_back(group);
        m.groups.push_back(group);
    }
    while (m.group_names.size() <= group) {
        std::string name = "g";  // (not "g" + ...: g++ 12 warns falsely on that)
        name += std::to_string(m.group_names.size());
        m.group_names.push_back(name);
    }
}

// Order-independent hash of all voxels (positions and values).
inline std::uint64_t model_hash(const voxel_model& m) {
    std::uint64_t sum = 0;
    m.for_each_voxel([&](glm::ivec3 p, std::uint8_t v) {
        std::uint64_t h = (std::uint64_t(std::uint32_t(p.x)) * 0x9E3779B97F4A7C15ull) ^
                          (std::uint64_t(std::uint32_t(p.y)) * 0xC2B2AE3D27D4EB4Full) ^
                          (std::uint64_t(std::uint32_t(p.z)) * 0x165667B19E3779F9ull) ^ (std::uint64_t(v) << 56);
        h ^= h >> 31;
        h *= 0xBF58476D1CE4E5B9ull;
        h ^= h >> 29;
        sum += h;
    });
    return sum;
}

// Runs f, which must throw voxray::error whose message contains every part.
template <class F, class... Parts>
void expect_error(F&& f, const Parts&... parts) {
    try {
        f();
        ADD_FAILURE() << "no voxray::error thrown";
    } catch (const voxray::error& e) {
        std::string msg = e.what();
        for (std::string_view part : {std::string_view(parts)...})
            EXPECT_NE(msg.find(part), std::string::npos) << "message '" << msg << "' lacks '" << part << "'";
    }
}

}  // namespace voxray::test
