// What reading bytes as a .vox file throws, for tests of the reader's errors.
#pragma once
#include <string>

#include "vox_bytes.hpp"
#include "voxray/core/error.hpp"
#include "voxray/io/vox_reader.hpp"

namespace voxray::test {

// The message of the voxray::error that reading `b` as the .vox file `name` throws;
// "(no error)" when it loads.
inline std::string vox_error_of(const vox_bytes::bytes& b, const io::vox_options& options = {},
                                const char* name = "test.vox") {
    try {
        io::read_vox_scene(b, name, options);
    } catch (const voxray::error& e) {
        return e.what();
    }
    return "(no error)";
}

}  // namespace voxray::test
