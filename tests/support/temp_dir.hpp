// A fresh folder for one test, named after the test, the process (tests of one binary run
// in sequence, binaries in parallel) and a count, removed when the test ends.
#pragma once
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

namespace voxray::test {

struct temp_dir {
    std::filesystem::path path;
    temp_dir() {
        static int made = 0;  // a test may hold several
        auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
        path = std::filesystem::temp_directory_path() / ("voxray_" + std::string(info->test_suite_name()) + "_" + info->name() +
                                                         "_" + std::to_string(::getpid()) + "_" + std::to_string(made++));
        std::filesystem::remove_all(path);
        std::filesystem::create_directories(path);
    }
    ~temp_dir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    temp_dir(const temp_dir&) = delete;
    temp_dir& operator=(const temp_dir&) = delete;
};

}  // namespace voxray::test
