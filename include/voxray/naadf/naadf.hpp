// NAADF: nested cells (page, chunk, block, voxel) whose empty cells carry axis-aligned
// distance fields, so a ray crosses empty space in cuboid-sized moves (the NAADF paper,
// sections 3.1-3.4; layout in naadf/layout.h, traversal in naadf/kernel.h). Voxel groups
// are deduplicated by hash, uniform blocks and chunks collapse, and the top level is a
// table of pages, so a sparse 16384^3 world costs megabytes.
#pragma once
#include <chrono>
#include <cstdint>
#include <span>
#include <string_view>

#include "voxray/core/blob.hpp"
#include "voxray/core/box.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/naadf/builder.hpp"

#define VOXRAY_KERNEL_NAME naadf
#define VOXRAY_KERNEL_FILE "voxray/naadf/kernel.h"
#include "voxray/kernels/cpu_kernel.inc"

namespace voxray {

class naadf {
public:
    static constexpr std::string_view name = "naadf";
    using kernel = kernels::naadf_kernel;

    naadf() : naadf(voxel_model{}) {}
    explicit naadf(const voxel_model& model, naadf_options options = {}) {
        auto start = std::chrono::steady_clock::now();
        auto built = naadf_detail::build(model, options);
        words_ = std::move(built.words);
        bounds_ = built.bounds;
        stats_ = built.stats;
        voxel_count_ = model.voxel_count();
        build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }

    std::span<const std::uint32_t> blob() const { return words_; }
    std::size_t bytes() const { return words_.size() * sizeof(std::uint32_t); }
    box3i bounds() const { return bounds_; }
    std::uint64_t voxel_count() const { return voxel_count_; }
    double build_seconds() const { return build_seconds_; }
    const naadf_stats& stats() const { return stats_; }

private:
    blob_words words_;
    box3i bounds_;
    naadf_stats stats_;
    std::uint64_t voxel_count_ = 0;
    double build_seconds_ = 0;
};

}  // namespace voxray
