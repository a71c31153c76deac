// The files of a sharded world build, in DIR/shards/ until the finishing step removes them:
//
//   plan.txt      what every shard must agree on: the source, the options, the number of
//                 shards and the split LOD (world/build/shard_plan.hpp). The first shard
//                 to start writes it; every other shard, rank and the finish compare
//                 theirs with it and refuse to go on, naming the first difference.
//   K-of-N.vxwm   shard K's chunks, written when the shard is done: a manifest
//                 (world/manifest.hpp) that lists only them. The finish merges these.
//   K-of-N.lock   held by shard K while it runs (two copies of one shard would race).
#pragma once
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <system_error>

#include "voxray/core/error.hpp"

namespace voxray {

struct shard_plan {
    std::uint32_t source_hash = 0;  // the source's own (the scene, resolution, tiling)
    int chunk_bits = 0, density = 0;
    std::uint32_t attributes = 0, colour_error_bits = 0;  // the float's bits: compared exactly
    unsigned shards = 0;
    int split_lod = 0;
};

inline std::filesystem::path shards_folder(const std::filesystem::path& dir) { return dir / "shards"; }
inline std::filesystem::path shard_plan_path(const std::filesystem::path& dir) { return shards_folder(dir) / "plan.txt"; }
inline std::filesystem::path shard_file(const std::filesystem::path& dir, unsigned k, unsigned n, const char* ext) {
    return shards_folder(dir) / (std::to_string(k) + "-of-" + std::to_string(n) + ext);
}

namespace shard_files_detail {

// The plan's fields in file order: name, and a pointer to the member.
struct field {
    const char* name;
    const char* meaning;  // what a difference in it means, for the error
    std::int64_t (*get)(const shard_plan&);
    void (*set)(shard_plan&, std::int64_t);
};
#define VOXRAY_PLAN_FIELD(member, meaning)                                                               \
    field {                                                                                              \
        #member, meaning, [](const shard_plan& p) { return std::int64_t(p.member); },                  \
            [](shard_plan& p, std::int64_t v) { p.member = decltype(p.member)(v); }                      \
    }
inline const field fields[] = {
    VOXRAY_PLAN_FIELD(source_hash, "another scene, mesh resolution or tiling"),
    VOXRAY_PLAN_FIELD(chunk_bits, "--chunk-bits"),
    VOXRAY_PLAN_FIELD(density, "--density"),
    VOXRAY_PLAN_FIELD(attributes, "--colours"),
    VOXRAY_PLAN_FIELD(colour_error_bits, "--colour-error"),
    VOXRAY_PLAN_FIELD(shards, "the N of --shard K/N, or the number of MPI ranks"),
    VOXRAY_PLAN_FIELD(split_lod, "the cut into units"),
};
#undef VOXRAY_PLAN_FIELD
inline constexpr const char* magic = "voxray-world-shard-plan 1";

}  // namespace shard_files_detail

inline std::string plan_text(const shard_plan& p) {
    std::string out = std::string(shard_files_detail::magic) + "\n";
    for (auto& f : shard_files_detail::fields) out += std::string(f.name) + " " + std::to_string(f.get(p)) + "\n";
    return out;
}

// Strict: the magic line, then every field once, in order, as "name value".
inline shard_plan read_plan(const std::filesystem::path& path) {
    std::ifstream in(path);
    if (!in) fail("world build: cannot read the shard plan ", path.string());
    std::string line;
    if (!std::getline(in, line) || line != shard_files_detail::magic)
        fail("world build: ", path.string(), " line 1: '", line, "' is not '", shard_files_detail::magic, "'");
    shard_plan p;
    int number = 1;
    for (auto& f : shard_files_detail::fields) {
        ++number;
        std::string name;
        long long value = 0;
        std::getline(in, line);
        std::istringstream words(line);
        if (!(words >> name >> value) || name != f.name || !(words >> std::ws).eof() || value < 0 || value > 0xffffffffll)
            fail("world build: ", path.string(), " line ", number, ": '", line, "' is not '", f.name, " VALUE' (0 to 2^32 - 1)");
        f.set(p, value);
    }
    return p;
}

// "" when the plans agree, else the first difference: "density 2 <where>, 3 here (--density)".
inline std::string plan_difference(const shard_plan& there, const shard_plan& mine, const std::string& where) {
    for (auto& f : shard_files_detail::fields)
        if (f.get(there) != f.get(mine))
            return std::string(f.name) + " " + std::to_string(f.get(there)) + " " + where + ", " + std::to_string(f.get(mine)) +
                   " here (" + f.meaning + ")";
    return "";
}

// Writes `mine` as the folder's plan unless one is there (link() does not replace, so of
// two shards starting at once one wins), then checks the plan there against `mine`.
inline void agree_on_plan(const std::filesystem::path& dir, const shard_plan& mine) {
    auto path = shard_plan_path(dir);
    std::filesystem::create_directories(path.parent_path());
    auto tmp = path;
    static std::atomic<unsigned> writers{0};  // shards may also be threads of one process
    tmp += "." + std::to_string(::getpid()) + "-" + std::to_string(writers++) + ".tmp";
    {
        std::ofstream out(tmp, std::ios::trunc);
        out << plan_text(mine);
        out.close();
        if (!out) fail("world build: cannot write ", tmp.string());
    }
    int linked = ::link(tmp.c_str(), path.c_str()), e = errno;
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    if (linked != 0 && e != EEXIST) fail("world build: cannot create ", path.string(), " (", std::strerror(e), ")");
    shard_plan there = read_plan(path);
    if (auto d = plan_difference(there, mine, "there"); !d.empty())
        fail("world build: ", dir.string(), " is being built with another plan (", path.string(), "): ", d,
             ": give every shard and the finish the same arguments, or remove ", shards_folder(dir).string(),
             " to start the sharded build over");
}

}  // namespace voxray
