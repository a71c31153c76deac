// The sparse voxel DAG (after Kämpe et al. and Aokana): an octree over a 2^D cube whose
// identical subtrees are stored once, with 4^3 bitmap leaves, and the voxels' payload
// decoupled from the geometry in depth-first order (exact bytes, or Aokana's lossy colour
// blocks). The memory anchor the other structures are measured against; read-only (a
// rebuild follows an edit). Layout: svdag/layout.h; traversal: svdag/kernel.h.
#pragma once
#include <chrono>
#include <cstdint>
#include <span>
#include <string_view>

#include "voxray/core/blob.hpp"
#include "voxray/core/box.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/svdag/builder.hpp"

#define VOXRAY_KERNEL_NAME svdag
#define VOXRAY_KERNEL_FILE "voxray/svdag/kernel.h"
#include "voxray/kernels/kernel_tag.inc"

namespace voxray {

// Exact attributes: a hit's material is the voxel's payload byte, as in every structure.
class svdag {
public:
    static constexpr std::string_view name = "svdag";
    using kernel = kernels::svdag_kernel;

    svdag() : svdag(voxel_model{}) {}
    explicit svdag(const voxel_model& model, svdag_options options = {}) { build(model, options); }

    void build(const voxel_model& model, svdag_options options = {}) {
        auto start = std::chrono::steady_clock::now();
        auto built = svdag_build::build(model, options);
        options_ = options;
        words_ = std::move(built.words);
        stats_ = built.stats;
        bounds_ = model.bounds();
        voxel_count_ = model.voxel_count();
        build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }

    std::span<const std::uint32_t> blob() const { return words_; }
    std::size_t bytes() const { return words_.size() * sizeof(std::uint32_t); }
    box3i bounds() const { return bounds_; }
    std::uint64_t voxel_count() const { return voxel_count_; }
    double build_seconds() const { return build_seconds_; }
    // Depth, node counts before and after merging, geometry and attribute bytes, colour error.
    const svdag_stats& stats() const { return stats_; }
    const svdag_options& options() const { return options_; }

private:
    blob_words words_;
    svdag_options options_;
    svdag_stats stats_;
    box3i bounds_;
    std::uint64_t voxel_count_ = 0;
    double build_seconds_ = 0;
};

// Colour blocks: a hit's material is the RGBA8 colour (r | g<<8 | b<<16 | a<<24) of the
// voxel's block, within options.colour_error of its palette colour per channel (plus the
// rounding to 8 bits). The same kernel; the blob's header says which encoding it holds.
class svdag_colours : public svdag {
public:
    static constexpr std::string_view name = "svdag-colours";
    // Hits carry colours, not palette indices: `voxray check` compares them to the
    // palette colour of the reference's material, within colour_tolerance.
    static constexpr bool material_is_colour = true;

    svdag_colours() : svdag_colours(voxel_model{}) {}
    // options.colour_error is the block error (0.05 by default); the encoding is always blocks.
    explicit svdag_colours(const voxel_model& model, svdag_options options = {})
        : svdag(model, with_blocks(options)) {}

    // How far a hit's colour may be from its voxel's palette colour, per channel in [0, 1].
    double colour_tolerance() const { return svdag_build::colour_tolerance(options().colour_error); }

private:
    static svdag_options with_blocks(svdag_options o) {
        o.attributes = svdag_attributes::colour_blocks;
        return o;
    }
};

}  // namespace voxray
