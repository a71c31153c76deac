// libFuzzer target for the .vox reader: any input must either read or throw
// voxray::error. Crashes, sanitizer reports, hangs and other exceptions are bugs.
// Built and run by run_fuzz.sh (ctest -L fuzz).
#include <cstddef>
#include <cstdint>
#include <span>

#include "voxray/io/vox_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    voxray::io::vox_options options;
    // Vary the options with the input so frame selection and hidden filtering run too.
    options.frame = int(size % 3);
    options.include_hidden = (size & 4) == 0;
    // Smaller budgets than the defaults keep each run fast; the shared scenes fit.
    options.max_instances = 1 << 14;
    options.max_node_visits = 1 << 16;
    options.max_placed_voxels = 1 << 22;
    options.max_model_bytes = std::uint64_t(256) << 20;
    try {
        auto scene = voxray::io::read_vox_scene(std::span<const std::uint8_t>(data, size), "fuzz.vox", options);
        // Touch the results so nothing is optimised away.
        volatile auto n = scene.model.voxel_count() + scene.stats.placed_voxels;
        (void)n;
        (void)scene.model.bounds();
    } catch (const voxray::error&) {
    }
    return 0;
}
