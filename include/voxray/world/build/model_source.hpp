// A voxel model as the source of a world build (world/build/world_build.hpp), optionally tiled:
// the model repeated `repeat` times along each axis, copy (i, j, k) shifted by the model's
// extent times (i, j, k) — a real scene made into a big world without holding the big
// world in memory (the copies are looked up, never stored).
#pragma once
#include <cstdint>
#include <algorithm>
#include <set>
#include <utility>
#include <vector>

#include "voxray/core/checksum.hpp"
#include "voxray/core/error.hpp"
#include "voxray/model/voxel_model.hpp"
#include "voxray/world/chunk_voxels.hpp"
#include "voxray/world/world_blob.hpp"

namespace voxray {

class model_source {
public:
    explicit model_source(const voxel_model& model, glm::ivec3 repeat = glm::ivec3(1)) : model_(&model), repeat_(repeat) {
        if (glm::any(glm::lessThan(repeat, glm::ivec3(1))))
            fail("model source: repeat ", repeat.x, " x ", repeat.y, " x ", repeat.z, " must be at least 1 on every axis");
        box3i b = model.bounds();
        tile_ = b.extent();
        for (int a = 0; a < 3; ++a)
            if (std::int64_t(b.min[a]) + std::int64_t(tile_[a]) * repeat[a] > voxel_model::coordinate_limit)
                fail("model source: ", repeat[a], " copies of ", tile_[a], " voxels pass the coordinate limit ",
                     voxel_model::coordinate_limit);
    }

    box3i bounds() const {
        box3i b = model_->bounds();
        if (b.empty()) return b;
        return {b.min, b.min + tile_ * repeat_};
    }
    // Of the voxels, the palette and the tiling; in chunk order, whatever order the
    // model's map iterates in.
    std::uint32_t hash() const {
        std::vector<std::pair<glm::ivec3, const voxel_model::chunk*>> chunks;
        model_->for_each_chunk([&](glm::ivec3 origin, const voxel_model::chunk& c) { chunks.emplace_back(origin, &c); });
        std::sort(chunks.begin(), chunks.end(), [](auto& a, auto& b) { return ivec3_less{}(a.first, b.first); });
        fnv64 h;
        for (auto& [origin, c] : chunks) {
            h.bytes(&origin, sizeof origin);
            h.bytes(c->voxels.data(), c->voxels.size());
        }
        for (int i = 0; i < 256; ++i) h.bytes(&model_->palette()[std::uint8_t(i)].colour, sizeof(rgba));
        h.bytes(&repeat_, sizeof repeat_);
        return std::uint32_t(h.h ^ (h.h >> 32));
    }
    // Cells any copy's model chunks fall in. Their list costs memory per copy and model
    // chunk, so a tiling past max_copy_chunks is refused before it is made.
    static constexpr std::uint64_t max_copy_chunks = std::uint64_t(1) << 25;
    std::vector<glm::ivec3> cells(const world_grid& g) const {
        std::uint64_t chunks = 0;
        model_->for_each_chunk([&](glm::ivec3, const voxel_model::chunk&) { ++chunks; });
        std::uint64_t copies = std::uint64_t(repeat_.x) * std::uint64_t(repeat_.y) * std::uint64_t(repeat_.z);
        if (copies * chunks > max_copy_chunks)
            fail("model source: ", repeat_.x, " x ", repeat_.y, " x ", repeat_.z, " copies of ", chunks, " model chunks are ",
                 copies * chunks, " copy chunks to place, more than the limit of ", max_copy_chunks, ": tile fewer copies");
        std::set<glm::ivec3, ivec3_less> out;
        for_each_copy([&](glm::ivec3 shift) {
            model_->for_each_chunk([&](glm::ivec3 origin, const voxel_model::chunk&) {
                glm::ivec3 lo = cell_of(origin + shift, g.origin, g.chunk_bits);
                glm::ivec3 hi = cell_of(origin + shift + voxel_model::chunk_edge - 1, g.origin, g.chunk_bits);
                for (int z = lo.z; z <= hi.z; ++z)
                    for (int y = lo.y; y <= hi.y; ++y)
                        for (int x = lo.x; x <= hi.x; ++x) out.insert({x, y, z});
            });
        });
        return {out.begin(), out.end()};
    }
    // The work of each of `cells` (sorted, as cells() gives them): the voxels of the model
    // chunks whose centre is in it, over every copy. An estimate that balances shards.
    std::vector<std::uint64_t> cell_work(const world_grid& g, const std::vector<glm::ivec3>& cells) const {
        std::vector<std::pair<glm::ivec3, std::uint64_t>> chunks;
        model_->for_each_chunk([&](glm::ivec3 origin, const voxel_model::chunk& c) {
            auto n = std::uint64_t(std::count_if(c.voxels.begin(), c.voxels.end(), [](std::uint8_t v) { return v != 0; }));
            chunks.emplace_back(origin + voxel_model::chunk_edge / 2, n);
        });
        std::vector<std::uint64_t> work(cells.size(), 0);
        for_each_copy([&](glm::ivec3 shift) {
            for (auto& [centre, n] : chunks) {
                glm::ivec3 cell = cell_of(centre + shift, g.origin, g.chunk_bits);
                auto it = std::lower_bound(cells.begin(), cells.end(), cell, ivec3_less{});
                if (it != cells.end() && *it == cell) work[std::size_t(it - cells.begin())] += n;
            }
        });
        return work;
    }
    // The cell's voxels: those of the model chunks that overlap the cell, of the copies
    // that can reach it (a few per axis, however many copies there are).
    chunk_voxels voxels(const world_grid& g, glm::ivec3 cell, bool colours) const {
        chunk_voxels out;
        box3i cell_box{g.origin + (cell << g.chunk_bits), g.origin + ((cell + 1) << g.chunk_bits)};
        for_each_copy_over(cell_box, [&](glm::ivec3 shift) {
            model_->for_each_chunk([&](glm::ivec3 origin, const voxel_model::chunk& c) {
                glm::ivec3 lo = origin + shift;
                if (glm::any(glm::greaterThanEqual(lo, cell_box.max)) ||
                    glm::any(glm::lessThanEqual(lo + voxel_model::chunk_edge, cell_box.min)))
                    return;
                for (int i = 0; i < voxel_model::chunk_voxels; ++i) {
                    std::uint8_t v = c.voxels[std::size_t(i)];
                    glm::ivec3 p = lo + voxel_model::local_position(i);
                    if (!v || !cell_box.contains(p)) continue;
                    out.keys.push_back(chunk_voxels::key(p - cell_box.min));
                    out.values.push_back(colours ? pack_rgba(model_->palette()[v].colour) : v);
                }
            });
        });
        out.sort();
        return out;
    }

private:
    template <class F>
    void for_each_copy(F&& f) const {
        for (int k = 0; k < repeat_.z; ++k)
            for (int j = 0; j < repeat_.y; ++j)
                for (int i = 0; i < repeat_.x; ++i) f(tile_ * glm::ivec3(i, j, k));
    }
    // The copies whose model chunks (which may reach a chunk edge past the model's
    // bounds on either side) can overlap `box`.
    template <class F>
    void for_each_copy_over(const box3i& box, F&& f) const {
        glm::ivec3 first(0), last(0);
        box3i b = model_->bounds();
        for (int a = 0; a < 3; ++a) {
            if (tile_[a] <= 0) return;
            std::int64_t reach_lo = std::int64_t(b.min[a]) - voxel_model::chunk_edge;   // below any chunk's min
            std::int64_t reach_hi = std::int64_t(b.max[a]) + voxel_model::chunk_edge;   // above any chunk's max
            auto floor_div = [](std::int64_t x, std::int64_t d) { return x >= 0 ? x / d : -((d - 1 - x) / d); };
            // copy i overlaps when reach_lo + tile * i < box.max and reach_hi + tile * i > box.min
            first[a] = int(std::max<std::int64_t>(0, floor_div(box.min[a] - reach_hi, tile_[a])));
            last[a] = int(std::min<std::int64_t>(repeat_[a] - 1, floor_div(box.max[a] - reach_lo, tile_[a])));
        }
        for (int k = first.z; k <= last.z; ++k)
            for (int j = first.y; j <= last.y; ++j)
                for (int i = first.x; i <= last.x; ++i) f(tile_ * glm::ivec3(i, j, k));
    }

    const voxel_model* model_;
    glm::ivec3 repeat_, tile_{0};
};

}  // namespace voxray
