// Where the real scenes live: $VOXRAY_DATA_DIR, else ../shared/data beside the checkout.
// Tests that need them call VOXRAY_REQUIRE_DATA() and skip only when the folder is absent.
#pragma once
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

namespace voxray::test {

inline std::optional<std::filesystem::path> data_dir() {
    std::filesystem::path dir = VOXRAY_TEST_DATA_DIR;
    if (const char* env = std::getenv("VOXRAY_DATA_DIR"); env && *env) dir = env;
    if (!std::filesystem::is_directory(dir)) return std::nullopt;
    return dir;
}

// Sorted list of files with the given extension in data_dir()/sub.
inline std::vector<std::filesystem::path> data_files(const char* sub, const char* ext) {
    std::vector<std::filesystem::path> files;
    auto dir = data_dir();
    if (!dir || !std::filesystem::is_directory(*dir / sub)) return files;
    for (auto& e : std::filesystem::directory_iterator(*dir / sub))
        if (e.path().extension() == ext) files.push_back(e.path());
    std::sort(files.begin(), files.end());
    return files;
}

}  // namespace voxray::test

#define VOXRAY_REQUIRE_DATA()                                                        \
    do {                                                                             \
        if (!::voxray::test::data_dir()) GTEST_SKIP() << "no test data folder found"; \
    } while (0)
