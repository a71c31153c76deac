// The reference structure: every voxel of the bounding box has an occupancy bit and a
// material byte, stored in 16^3 chunks that are allocated only where a voxel is solid.
// Its traversal (dense_grid/kernel.h) steps one voxel at a time: slow but simple and
// exact, which makes it the oracle every other structure and backend is checked against.
#pragma once
#include <chrono>
#include <cstdint>
#include <span>
#include <string_view>

#include "voxray/core/bits.hpp"
#include "voxray/core/box.hpp"
#include "voxray/dense_grid/layout.h"
#include "voxray/model/voxel_model.hpp"
#include "voxray/core/blob.hpp"

#define VOXRAY_KERNEL_NAME dense_grid
#define VOXRAY_KERNEL_FILE "voxray/dense_grid/kernel.h"
#include "voxray/kernels/kernel_tag.inc"

namespace voxray {

class dense_grid {
public:
    static constexpr std::string_view name = "dense";
    using kernel = kernels::dense_grid_kernel;
    // The chunk table is dense over the bounding box: keep it within 2^28 entries (1 GiB).
    static constexpr std::uint64_t max_table_entries = std::uint64_t(1) << 28;

    dense_grid() { build(voxel_model{}); }
    explicit dense_grid(const voxel_model& model) { build(model); }

    void build(const voxel_model& model) {
        auto start = std::chrono::steady_clock::now();
        bounds_ = model.bounds();
        glm::ivec3 extent = bounds_.extent();
        glm::uvec3 chunks = (glm::uvec3(extent) + 15u) / 16u;
        std::uint64_t table_entries = std::uint64_t(chunks.x) * chunks.y * chunks.z;
        if (table_entries > max_table_entries)
            fail("dense grid: a bounding box of ", extent.x, " x ", extent.y, " x ", extent.z,
                 " voxels needs ", table_entries, " chunk table entries, above the limit of ", max_table_entries);

        // Chunks of the model are 16^3 too, but aligned to world coordinates; ours are
        // aligned to the bounding box, so a model chunk can touch up to 8 of ours.
        std::uint64_t header = VX_DG_HEADER_WORDS;
        std::vector<std::uint32_t> table(table_entries, VX_DG_EMPTY_CHUNK);
        std::uint32_t chunk_count = 0;
        model.for_each_voxel([&](glm::ivec3 p, std::uint8_t) {
            auto q = glm::uvec3(p - bounds_.min);
            auto& slot = table[VX_DG_CHUNK_SLOT(std::uint64_t(q.x), q.y, q.z, chunks.x, std::uint64_t(chunks.x) * chunks.y)];
            if (slot == VX_DG_EMPTY_CHUNK) slot = chunk_count++;
        });
        std::uint64_t data = header + table_entries;
        std::uint64_t total = data + std::uint64_t(chunk_count) * VX_DG_CHUNK_WORDS;
        check_blob_size("dense grid", total);

        words_.assign(total, 0u);
        words_[VX_DG_HEADER_MAGIC] = VX_DG_MAGIC;
        words_[VX_DG_HEADER_VERSION] = VX_DG_VERSION;
        for (int a = 0; a < 3; ++a) {
            words_[VX_DG_HEADER_ORIGIN + a] = std::uint32_t(bounds_.min[a]);
            words_[VX_DG_HEADER_EXTENT + a] = std::uint32_t(extent[a]);
            words_[VX_DG_HEADER_CHUNKS + a] = chunks[a];
        }
        words_[VX_DG_HEADER_TABLE] = std::uint32_t(header);
        words_[VX_DG_HEADER_DATA] = std::uint32_t(data);
        words_[VX_DG_HEADER_CHUNK_COUNT] = chunk_count;
        std::copy(table.begin(), table.end(), words_.begin() + header);

        model.for_each_voxel([&](glm::ivec3 p, std::uint8_t value) {
            auto q = glm::uvec3(p - bounds_.min);
            std::uint32_t entry =
                table[VX_DG_CHUNK_SLOT(std::uint64_t(q.x), q.y, q.z, chunks.x, std::uint64_t(chunks.x) * chunks.y)];
            std::uint32_t local = VX_DG_LOCAL(q.x, q.y, q.z);
            std::uint32_t* record = words_.data() + data + std::uint64_t(entry) * VX_DG_CHUNK_WORDS;
            bits::set(record, local);
            record[VX_DG_MATERIAL_WORD(local)] |= std::uint32_t(value) << VX_DG_MATERIAL_SHIFT(local);
        });
        voxel_count_ = model.voxel_count();
        build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }

    std::span<const std::uint32_t> blob() const { return words_; }
    std::size_t bytes() const { return words_.size() * sizeof(std::uint32_t); }
    box3i bounds() const { return bounds_; }
    std::uint64_t voxel_count() const { return voxel_count_; }
    double build_seconds() const { return build_seconds_; }

private:
    blob_words words_;
    box3i bounds_;
    std::uint64_t voxel_count_ = 0;
    double build_seconds_ = 0;
};

}  // namespace voxray
