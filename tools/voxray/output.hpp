// The tool's output files, whose failures must not pass silently: a full disk, a
// directory or an unwritable path named as an output is an error naming the path, never
// exit 0 with an empty file. A stream is checked once its bytes are flushed (close()),
// because that is when a full disk shows.
#pragma once
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "voxray/core/error.hpp"

namespace voxray::tool {

// An output file: opened at once (failing with the path), written, then finish()ed,
// which flushes and fails with the path when any write did not reach the file.
class output_file {
public:
    output_file(std::string path, std::string_view option, std::ios::openmode mode = std::ios::trunc)
        : path_(std::move(path)), option_(option), out_(path_, std::ios::binary | std::ios::out | mode) {
        if (!out_) fail(option_, " ", path_, ": cannot be written (", std::strerror(errno), ")");
    }
    std::ofstream& stream() { return out_; }
    void finish() {
        out_.close();
        if (!out_) fail(option_, " ", path_, ": writing failed (is the disk full?)");
    }

private:
    std::string path_, option_;
    std::ofstream out_;
};

// Writes `bytes` to `path` through path + ".tmp" and a rename, so that a reader never
// sees half a file and a failed write leaves none.
inline void write_file_atomically(const std::filesystem::path& path, std::string_view bytes, std::string_view what) {
    auto tmp = path;
    tmp += ".tmp";
    std::error_code ec;
    {
        output_file out(tmp.string(), what);
        out.stream().write(bytes.data(), std::streamsize(bytes.size()));
        try {
            out.finish();
        } catch (const error&) {
            std::filesystem::remove(tmp, ec);
            throw;
        }
    }
    std::filesystem::rename(tmp, path, ec);
    if (ec) {
        std::error_code ignored;
        std::filesystem::remove(tmp, ignored);
        fail(what, " ", path.string(), ": cannot rename ", tmp.string(), " into place (", ec.message(), ")");
    }
}

}  // namespace voxray::tool
