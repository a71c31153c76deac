// The first line of a results file: what ran, where, built how, from which commit.
#pragma once
#include <sys/utsname.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "voxray_build_info.hpp"  // VOXRAY_GIT_COMMIT, written at build time

namespace voxray::tool {

// The CPU clock in Hz as the kernel reports it (the largest "cpu MHz" in /proc/cpuinfo),
// 0 when unknown. Cycles per ray-step = threads x clock / (rays/s x steps/ray).
inline double cpu_clock_hz() {
    std::ifstream in("/proc/cpuinfo");
    double best = 0;
    for (std::string line; std::getline(in, line);)
        if (line.rfind("cpu MHz", 0) == 0) {
            auto colon = line.find(':');
            if (colon != std::string::npos) best = std::max(best, std::atof(line.c_str() + colon + 1) * 1e6);
        }
    return best;
}

inline std::string cpu_model() {
    std::ifstream in("/proc/cpuinfo");
    for (std::string line; std::getline(in, line);)
        if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) return line.substr(line.find(':') + 2);
    return "unknown";
}

inline std::string compiler_name() {
#if defined(__clang__)
    return "clang " __clang_version__;
#elif defined(__GNUC__)
    return "g++ " __VERSION__;
#else
    return "unknown";
#endif
}

inline std::string utc_now() {
    std::time_t now = std::time(nullptr);
    char text[32];
    std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
    return text;
}

// This process's command line, as the results file records it.
inline std::string own_command_line() {
    std::ifstream in("/proc/self/cmdline", std::ios::binary);
    std::string all((std::istreambuf_iterator<char>(in)), {}), out;
    for (char c : all) out += c ? c : ' ';
    while (!out.empty() && out.back() == ' ') out.pop_back();
    return out;
}

// `simd_width`: lanes of the CPU backend's stream as chosen at run time.
inline nlohmann::json results_header(const std::string& command_line, unsigned simd_width) {
    utsname os{};
    uname(&os);
    return {{"type", "header"},
            {"format", "voxray-bench-1"},
            {"started_utc", utc_now()},
            {"command", command_line},
            {"git_commit", VOXRAY_GIT_COMMIT},
            {"compiler", compiler_name()},
            {"build_type", VOXRAY_BUILD_TYPE},
            {"build_flags", VOXRAY_BUILD_FLAGS},
            {"machine",
             {{"cpu_model", cpu_model()},
              {"cores", std::thread::hardware_concurrency()},
              {"clock_hz", cpu_clock_hz()},
              {"simd_width", simd_width},
              {"os", std::string(os.sysname) + " " + os.release}}}};
}

}  // namespace voxray::tool
