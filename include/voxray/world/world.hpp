// The chunked world (after Aokana): a grid of chunks, each its own sparse voxel DAG of
// C^3 voxels (C = 2^chunk_bits, 256 by default), and a LOD chain above them in which 8
// chunks of LOD n-1 make one chunk of LOD n at the same resolution (world/lod.hpp). The
// rays see one cut through the chain (show_lod, show): every cell is traced through the
// one chunk that stands for it. Layout: world/layout.h; traversal: world/kernel.h.
//
// This type builds every chunk of every LOD in memory from a voxel model: a world that
// fits in memory, and the reference a streamed world (chunks in files, a budget of them
// resident) is held to.
#pragma once
#include <array>
#include <chrono>
#include <cstdint>
#include <map>
#include <span>
#include <string_view>
#include <tuple>
#include <utility>
#include <vector>

#include "voxray/core/box.hpp"
#include "voxray/model/build_threads.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/world/build/chunk_dag.hpp"
#include "voxray/world/chunk_voxels.hpp"
#include "voxray/world/lod.hpp"
#include "voxray/world/world_blob.hpp"

#define VOXRAY_KERNEL_NAME world
#define VOXRAY_KERNEL_FILE "voxray/world/kernel.h"
#include "voxray/kernels/kernel_tag.inc"

namespace voxray {

struct world_options {
    int chunk_bits = 8;            // C = 2^chunk_bits voxels a side, in [4, 10]
    svdag_attributes attributes = svdag_attributes::exact;
    float colour_error = 0.05f;    // colour blocks: the largest channel error in a block
    int density = 2;               // children (of 8) a LOD voxel needs
    unsigned threads = 0;          // build threads; 0: all hardware threads
};

struct world_stats {
    int top_lod = 0;
    std::vector<std::uint64_t> chunks, voxels, bytes;  // per LOD: non-empty chunks, solid voxels, DAG bytes
    std::uint64_t shown_chunks = 0, shown_bytes = 0;   // in the current cut (the blob)
    std::vector<std::pair<const char*, double>> figures() const {
        std::vector<std::pair<const char*, double>> f = {{"top_lod", top_lod},
                                                         {"shown_chunks", double(shown_chunks)},
                                                         {"shown_bytes", double(shown_bytes)}};
        static constexpr const char* chunk_names[] = {"lod0_chunks", "lod1_chunks", "lod2_chunks", "lod3_chunks"};
        static constexpr const char* byte_names[] = {"lod0_bytes", "lod1_bytes", "lod2_bytes", "lod3_bytes"};
        for (std::size_t n = 0; n < chunks.size() && n < 4; ++n) {
            f.push_back({chunk_names[n], double(chunks[n])});
            f.push_back({byte_names[n], double(bytes[n])});
        }
        return f;
    }
};

class chunked_world {
public:
    static constexpr std::string_view name = "world";
    using kernel = kernels::world_kernel;

    chunked_world() : chunked_world(voxel_model{}) {}
    explicit chunked_world(const voxel_model& model, world_options options = {}) { build(model, options); }

    void build(const voxel_model& model, world_options options = {}) {
        auto start = std::chrono::steady_clock::now();
        options_ = options;
        bounds_ = model.bounds();
        voxel_count_ = model.voxel_count();
        grid_ = world_grid::fit(bounds_, options.chunk_bits);
        bool colours = options.attributes == svdag_attributes::colour_blocks;
        chunk_dag_options dag{options.attributes, options.colour_error};
        chunks_.assign(std::size_t(grid_.top_lod) + 1, {});
        stats_ = {};
        stats_.top_lod = grid_.top_lod;

        // LOD 0 from the model, each LOD from the one below; every level's DAGs in parallel.
        auto level = cut_into_cells(model, grid_.origin, grid_.chunk_bits, colours);
        for (int n = 0; n <= grid_.top_lod; ++n) {
            build_level(n, level, dag);
            if (n == grid_.top_lod) break;
            std::map<glm::ivec3, std::array<const chunk_voxels*, 8>, ivec3_less> groups;
            for (auto& [cell, v] : level) {
                auto& g = groups.try_emplace(cell >> 1).first->second;
                g[std::size_t((cell.x & 1) | ((cell.y & 1) << 1) | ((cell.z & 1) << 2))] = &v;
            }
            std::map<glm::ivec3, chunk_voxels, ivec3_less> next;
            for (auto& [parent, children] : groups) {
                auto v = downsample(children, grid_.chunk_bits, options.density, colours);
                if (!v.empty()) next.emplace(parent, std::move(v));
            }
            level = std::move(next);
        }
        show_lod(0);
        build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }

    // Every region through its chunk of LOD min(lod, top_lod).
    void show_lod(int lod) {
        lod = std::clamp(lod, 0, grid_.top_lod);
        std::vector<placement> cut;
        for (auto& [cell, c] : chunks_[std::size_t(lod)]) cut.push_back({c.key, &c});
        show(cut);
    }
    // Any cut: each placement stands for the cells of its region, finer ones over coarser.
    void show(std::span<const placement> cut) {
        words_ = pack_world(grid_, cut, options_.attributes);
        stats_.shown_chunks = 0;
        stats_.shown_bytes = 0;
        for (auto& p : cut)
            if (p.chunk && !p.chunk->empty()) ++stats_.shown_chunks, stats_.shown_bytes += p.chunk->dag.size() * 4;
    }
    // The chunk of that key, or nullptr when that region has no voxels at that LOD.
    const chunk_record* find(chunk_key key) const {
        if (key.lod < 0 || key.lod > grid_.top_lod) return nullptr;
        auto& level = chunks_[std::size_t(key.lod)];
        auto it = level.find(key.cell);
        return it == level.end() ? nullptr : &it->second;
    }

    std::span<const std::uint32_t> blob() const { return words_; }
    std::size_t bytes() const { return words_.size() * sizeof(std::uint32_t); }
    box3i bounds() const { return bounds_; }
    std::uint64_t voxel_count() const { return voxel_count_; }
    double build_seconds() const { return build_seconds_; }
    const world_grid& grid() const { return grid_; }
    const world_options& options() const { return options_; }
    const world_stats& stats() const { return stats_; }

private:
    void build_level(int n, const std::map<glm::ivec3, chunk_voxels, ivec3_less>& level, const chunk_dag_options& dag) {
        std::vector<std::pair<glm::ivec3, const chunk_voxels*>> work;
        for (auto& [cell, v] : level) work.emplace_back(cell, &v);
        std::vector<chunk_record> built(work.size());
        unsigned threads = resolve_build_threads(options_.threads, work.size());
        run_build_threads(threads, [&](unsigned t) {
            for (std::size_t i = t; i < work.size(); i += threads)
                built[i] = build_chunk(*work[i].second, chunk_key{n, work[i].first}, grid_.chunk_bits, dag);
        });
        auto& out = chunks_[std::size_t(n)];
        stats_.chunks.push_back(0), stats_.voxels.push_back(0), stats_.bytes.push_back(0);
        for (auto& c : built) {
            ++stats_.chunks.back();
            stats_.voxels.back() += c.voxel_count;
            stats_.bytes.back() += c.dag.size() * 4;
            out.emplace(c.key.cell, std::move(c));
        }
    }

    world_options options_;
    world_grid grid_;
    std::vector<std::map<glm::ivec3, chunk_record, ivec3_less>> chunks_;  // per LOD, by cell
    world_stats stats_;
    blob_words words_;
    box3i bounds_;
    std::uint64_t voxel_count_ = 0;
    double build_seconds_ = 0;
};

// The same world with 16^3 chunks: many chunks, many chunk borders and LODs even on small
// scenes (the conformance suite's), and the smallest chunk a world allows.
class chunked_world_16 : public chunked_world {
public:
    static constexpr std::string_view name = "world-16";
    chunked_world_16() : chunked_world_16(voxel_model{}) {}
    explicit chunked_world_16(const voxel_model& model, world_options options = {})
        : chunked_world(model, with_bits(options)) {}

private:
    static world_options with_bits(world_options o) {
        o.chunk_bits = 4;
        return o;
    }
};

}  // namespace voxray
