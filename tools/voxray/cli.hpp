// Shared pieces of the tool's command line (CLI11): the scene options, name lists checked
// against what this build knows, and checks that must pass before any scene loads (an
// output path that can be written, enough memory for a request).
#pragma once
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "engines.hpp"
#include "voxray/core/error.hpp"

namespace voxray::tool {

// A subcommand and what runs it once parsed (returns the exit code).
struct command {
    CLI::App* app = nullptr;
    std::function<int()> run;
};

command add_info(CLI::App& parent);
command add_render(CLI::App& parent);
command add_check(CLI::App& parent);
command add_bench(CLI::App& parent);
command add_world_build(CLI::App& parent);
command add_world_fly(CLI::App& parent);
command add_mesh(CLI::App& parent);
command add_mesh_bench(CLI::App& parent);
command add_appearance_bench(CLI::App& parent);
command add_appearance_world_bench(CLI::App& parent);
command add_appearance_walk_bench(CLI::App& parent);

inline const std::vector<std::string> ray_set_names = {"primary", "secondary", "shadow"};

inline std::vector<std::string> split_names(const std::string& s) {
    std::vector<std::string> out;
    std::string item;
    for (char c : s + ",") {
        if (c != ',') item += c;
        else if (!item.empty()) out.push_back(item), item.clear();
    }
    return out;
}

// The names as one comma-separated list (split_names' inverse).
inline std::string join_names(const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ",") + n;
    return out;
}

// A CLI11 check for a comma-separated list of names from `known`: at least one, each known.
inline CLI::Validator names_from(std::vector<std::string> known, std::string what) {
    return CLI::Validator(
        [known, what](std::string& value) -> std::string {
            auto names = split_names(value);
            std::string list;
            for (auto& k : known) list += (list.empty() ? "" : ", ") + k;
            if (names.empty()) return "empty list: name at least one " + what + " of " + list;
            for (auto& n : names)
                if (std::find(known.begin(), known.end(), n) == known.end())
                    return "unknown or unavailable " + what + " '" + n + "' (known: " + list + ")";
            return "";
        },
        "NAME[,NAME...]");
}

// CLI::Range for real numbers that also refuses NaN (every comparison with NaN is false,
// so a plain range lets it through).
inline CLI::Validator finite_range(double lo, double hi) {
    return CLI::Validator(
        [lo, hi](std::string& value) -> std::string {
            double v = 0;
            if (!CLI::detail::lexical_cast(value, v)) return "Value " + value + " is not a number";
            if (!(v >= lo && v <= hi)) return "Value " + value + " not in range " + CLI::detail::to_string(lo) + " to " + CLI::detail::to_string(hi);
            return "";
        },
        "FLOAT in [" + CLI::detail::to_string(lo) + " - " + CLI::detail::to_string(hi) + "]");
}

inline std::vector<std::string> all_structure_names() { return split_names(structure_names(",")); }

// Fails now, before any work, when `path` cannot be written; leaves no file behind.
inline void require_writable(const std::string& path, const std::string& option) {
    bool existed = std::filesystem::exists(path);
    { std::ofstream probe(path, std::ios::app); if (!probe) fail(option, " ", path, ": cannot be written (", std::strerror(errno), ")"); }
    if (!existed) std::filesystem::remove(path);
}

// Creates `path` (and its parents) and fails now, before any work, unless a file can be
// written in it.
inline void require_writable_folder(const std::string& path, const std::string& option) {
    std::error_code ec;
    std::filesystem::create_directories(path, ec);
    if (ec || !std::filesystem::is_directory(path))
        fail(option, " ", path, ": cannot be made a folder (", ec ? ec.message() : "it is a file", ")");
    // A probe of this process's own: ranks of one run probe the same folder at once, and with
    // one shared name a rank could re-create the probe another had just removed, and keep it.
    std::string probe =
        ".voxray-write-probe-" + std::to_string(::getpid()) + "-" + std::to_string(std::random_device{}());
    require_writable((std::filesystem::path(path) / probe).string(), option);
}

// Bytes this process may still allocate: the smaller of the kernel's MemAvailable and the
// address-space limit (ulimit -v); 0 when neither is known.
inline std::uint64_t available_memory() {
    std::uint64_t available = 0;
    std::ifstream in("/proc/meminfo");
    for (std::string key; in >> key;) {
        std::uint64_t kib = 0;
        in >> kib;
        if (key == "MemAvailable:") available = kib * 1024;
        in.ignore(1 << 10, '\n');
    }
    rlimit limit{};
    if (getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
        available = available ? std::min<std::uint64_t>(available, limit.rlim_cur) : limit.rlim_cur;
    return available;
}

// Fails with the numbers when a request needs more memory than there is.
inline void require_memory(std::uint64_t bytes, const std::string& what) {
    std::uint64_t available = available_memory();
    if (available && bytes > available)
        fail(what, " needs ", double(bytes) / double(1ull << 30), " GiB but only ", double(available) / double(1ull << 30),
             " GiB are available (MemAvailable, ulimit -v): ask for less");
}

}  // namespace voxray::tool
