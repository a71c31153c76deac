// libFuzzer target for every file format of the malformed-input test (its all_formats():
// .obj, .ply, .vxbm, .vxna, .vxck, .vxwm, and .vox, which fuzz_vox.cpp fuzzes with its
// options varied too). VOXRAY_FUZZ_FORMAT names the format; any input must load or throw
// voxray::error, as must the input with its checksum recomputed (the format's reseal), so
// that mutations reach the checks behind the checksum. Crashes, sanitizer reports, hangs
// and other exceptions are bugs. Built and run by run_fuzz.sh.
//
//   VOXRAY_FUZZ_FORMAT=vxck ./fuzz_formats CORPUS      fuzz one format
//   VOXRAY_FUZZ_SEEDS=DIR                              also write its valid samples to DIR first
//   VOXRAY_FUZZ_LIST=1 ./fuzz_formats                  print the format names and exit
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "../malformed/formats.hpp"

namespace {

using namespace voxray::test::malformed;

const input_format& chosen_format() {
    static const input_format f = [] {
        const char* name = std::getenv("VOXRAY_FUZZ_FORMAT");
        std::string want = name ? name : "";
        for (auto& format : all_formats())
            if (format.name == want) return format;
        std::fprintf(stderr, "fuzz_formats: VOXRAY_FUZZ_FORMAT='%s' is not a format; VOXRAY_FUZZ_LIST=1 lists them\n",
                     want.c_str());
        std::exit(2);
    }();
    return f;
}

void load_or_error(const input_format& f, const bytes& b) {
    try {
        f.load(b);
    } catch (const voxray::error&) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    if (std::getenv("VOXRAY_FUZZ_LIST")) {
        for (auto& f : all_formats()) std::printf("%s\n", f.name.c_str());
        std::exit(0);
    }
    const input_format& f = chosen_format();
    if (const char* dir = std::getenv("VOXRAY_FUZZ_SEEDS"))
        for (std::size_t i = 0; i < f.samples.size(); ++i)
            write_file(std::filesystem::path(dir) / ("sample" + std::to_string(i) + "." + f.name), f.samples[i]);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const input_format& f = chosen_format();
    bytes b(data, data + size);
    load_or_error(f, b);
    if (f.reseal) {
        f.reseal(b);
        load_or_error(f, b);
    }
    return 0;
}
