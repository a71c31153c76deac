// The CPU mesher: one 64^3 chunk -> quads in POP order (meshing/layout.h).
//
// Per face direction:
//  1. Face masks by bitwise culling of 64-bit occupancy rows: a +Z face wherever a voxel
//     is solid and the one above is not is `row(y, z) & ~row(y, z + 1)`, 64 faces at once.
//     X faces have their bits along the normal, so their masks are transposed (64 x 64
//     bits) into planes whose bits run along Y.
//  2. Greedy merging per plane: a run of set bits with one material (and one AO pattern
//     when AO is on) is grown along the rows while the next row holds the same run.
//  3. POP order fused into emission: each quad's level (layout.h) is computed as it is made
//     and the quad goes straight into its level's bucket; a face's buckets are appended
//     coarse to fine and the table records the prefixes.
//
// Faces with a corner on a chunk side (u or v at 0 or 64) are never merged: the border ring.
// Then every merged quad lies, closed, inside one cell of the chunk grid (a chunk's inside,
// a side's inside), which meshing/pop.h morphs with one t, and every edge that leaves a
// cell is one voxel long and so holds no T-junction: no cracks (docs/meshing.md, "Cracks").
#pragma once
#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <vector>

#include "voxray/core/ray_hit_layout.h"
#include "voxray/meshing/bit_transpose.hpp"
#include "voxray/meshing/chunk.hpp"
#include "voxray/meshing/chunk_mesh.hpp"
#include "voxray/meshing/face_ao.hpp"
#include "voxray/meshing/layout.h"

namespace voxray::meshing {

struct mesher_options {
    bool ambient_occlusion = false;  // 4 x 2 AO bits per quad; merging stops where AO differs
    bool pop_order = true;           // false: emission order, every quad in every prefix (times POP apart)
};

// The number of POP levels a quad spanning [u0, u0 + w) x [v0, v0 + h) survives: per axis
// the bit length of lo XOR hi, the smaller of the two, at most VX_MESH_MAX_LEVEL. Chunk
// origins are multiples of 64, so chunk-local coordinates give the world's answer.
inline int quad_level(int u0, int w, int v0, int h) {
    auto levels = [](unsigned lo, unsigned hi) { return int(std::bit_width(lo ^ hi)); };
    return std::min({levels(unsigned(u0), unsigned(u0 + w)), levels(unsigned(v0), unsigned(v0 + h)), VX_MESH_MAX_LEVEL});
}

class mesher {
public:
    explicit mesher(mesher_options options = {}) : options_(options), planes_(chunk_edge * chunk_edge) {}

    const mesher_options& options() const { return options_; }

    void mesh(const chunk_voxels& chunk, chunk_mesh& out) {
        out.origin = chunk.origin;
        out.words.clear();
        for (int face = 0; face < VX_MESH_FACES; ++face) {
            build_planes(chunk, face);
            if (options_.ambient_occlusion) merge_face<true>(chunk, face);
            else merge_face<false>(chunk, face);
            append_face(face, out);
        }
    }

    chunk_mesh mesh(const chunk_voxels& chunk) {
        chunk_mesh m;
        mesh(chunk, m);
        return m;
    }

private:
    // planes_[layer * 64 + row]: the faces of direction `face` in the plane `layer` along
    // the normal. Z faces: rows y, bits x. Y faces: rows z, bits x. X faces: rows z, bits y.
    void build_planes(const chunk_voxels& c, int face) {
        const std::uint64_t* rows = c.rows.data();
        auto row = [&](int y, int z) { return rows[chunk_voxels::row_index(y, z)]; };
        const int n = chunk_edge;
        switch (face) {
            case VX_FACE_POS_Z:
            case VX_FACE_NEG_Z: {
                int dz = face == VX_FACE_POS_Z ? 1 : -1;
                for (int z = 0; z < n; ++z)
                    for (int y = 0; y < n; ++y) planes_[z * n + y] = row(y, z) & ~row(y, z + dz);
                break;
            }
            case VX_FACE_POS_Y:
            case VX_FACE_NEG_Y: {
                int dy = face == VX_FACE_POS_Y ? 1 : -1;
                for (int y = 0; y < n; ++y)
                    for (int z = 0; z < n; ++z) planes_[y * n + z] = row(y, z) & ~row(y + dy, z);
                break;
            }
            default: {  // X: faces along x in each row, then each z slice transposed
                bool positive = face == VX_FACE_POS_X;
                std::array<std::uint64_t, chunk_edge> slice;
                for (int z = 0; z < n; ++z) {
                    std::uint64_t any = 0;
                    for (int y = 0; y < n; ++y) {
                        int r = chunk_voxels::row_index(y, z);
                        std::uint64_t s = rows[r];
                        std::uint64_t next = positive ? (s >> 1) | (std::uint64_t(c.x_hi[r] != 0) << 63)
                                                      : (s << 1) | std::uint64_t(c.x_lo[r] != 0);
                        slice[y] = s & ~next;
                        any |= slice[y];
                    }
                    if (any) transpose64(slice.data());
                    for (int x = 0; x < n; ++x) planes_[x * n + z] = any ? slice[x] : 0;
                }
                break;
            }
        }
    }

    template <bool AO>
    void merge_face(const chunk_voxels& c, int face) {
        for (auto& b : buckets_) b.clear();
        const int n = chunk_edge;
        const int normal = VX_MESH_NORMAL_AXIS(face);
        // Plane coordinates (layer, row, bit) -> voxel, and which of rows and bits runs along u.
        auto voxel = [normal](int layer, int r, int b) -> glm::ivec3 {
            if (normal == 2) return {b, r, layer};
            if (normal == 1) return {b, layer, r};
            return {layer, b, r};
        };
        const bool bits_along_u = normal != 1;
        auto key = [&](int layer, int r, int b) -> std::uint32_t {
            glm::ivec3 p = voxel(layer, r, b);
            std::uint32_t k = c.material_at(p.x, p.y, p.z);
            if constexpr (AO) k |= std::uint32_t(face_ao(c, p, face)) << 16;
            return k;
        };
        auto emit = [&](int layer, int r, int b, int run, int rows_merged, std::uint32_t k) {
            glm::ivec3 p = voxel(layer, r, b);
            int w = bits_along_u ? run : rows_merged, h = bits_along_u ? rows_merged : run;
            int u0 = p[VX_MESH_U_AXIS(face)], v0 = p[VX_MESH_V_AXIS(face)];
            int level = options_.pop_order ? quad_level(u0, w, v0, h) : VX_MESH_MAX_LEVEL;
            std::uint32_t ao = AO ? (k >> 16) : VX_MESH_AO_OPEN;
            std::uint32_t w0 = VX_MESH_WORD0(std::uint32_t(p.x), std::uint32_t(p.y), std::uint32_t(p.z), std::uint32_t(w),
                                             std::uint32_t(h));
            std::uint32_t w1 = VX_MESH_WORD1(k & 0xFFFFu, ao, std::uint32_t(face), std::uint32_t(level));
            buckets_[level].push_back(std::uint64_t(w0) | (std::uint64_t(w1) << 32));
        };
        auto emit_units = [&](int layer, int r, std::uint64_t bits) {
            for (; bits; bits &= bits - 1) {
                int b = std::countr_zero(bits);
                emit(layer, r, b, 1, 1, key(layer, r, b));
            }
        };
        for (int layer = 0; layer < n; ++layer) {
            std::uint64_t* plane = planes_.data() + layer * n;
            // The border ring: faces with a corner on a chunk side stay unit quads.
            constexpr std::uint64_t ring_bits = 1u | (std::uint64_t(1) << 63);
            emit_units(layer, 0, plane[0]);
            emit_units(layer, n - 1, plane[n - 1]);
            plane[0] = plane[n - 1] = 0;
            for (int r = 1; r < n - 1; ++r) {
                emit_units(layer, r, plane[r] & ring_bits);
                plane[r] &= ~ring_bits;
            }
            for (int r = 1; r < n - 1; ++r) {
                while (std::uint64_t bits = plane[r]) {
                    int b0 = std::countr_zero(bits);
                    std::uint32_t k = key(layer, r, b0);
                    int longest = std::countr_one(bits >> b0);
                    int run = 1;
                    while (run < longest && key(layer, r, b0 + run) == k) ++run;
                    std::uint64_t span = (run == 64 ? ~std::uint64_t(0) : ((std::uint64_t(1) << run) - 1)) << b0;
                    plane[r] &= ~span;
                    int rows_merged = 1;
                    for (int r2 = r + 1; r2 < n - 1 && (plane[r2] & span) == span; ++r2) {
                        bool same = true;
                        for (int b = b0; b < b0 + run && same; ++b) same = key(layer, r2, b) == k;
                        if (!same) break;
                        plane[r2] &= ~span;
                        ++rows_merged;
                    }
                    emit(layer, r, b0, run, rows_merged, k);
                }
            }
        }
    }

    // Appends face f's buckets coarse to fine and records its prefixes.
    void append_face(int face, chunk_mesh& out) {
        for (int level = VX_MESH_MAX_LEVEL; level >= 1; --level) {
            const auto& b = buckets_[level];
            std::size_t at = out.words.size();
            out.words.resize(at + b.size() * VX_MESH_QUAD_WORDS);
            for (std::size_t i = 0; i < b.size(); ++i) {
                out.words[at + 2 * i] = std::uint32_t(b[i]);
                out.words[at + 2 * i + 1] = std::uint32_t(b[i] >> 32);
            }
            // Drawn at level of detail i while i < level: this bucket ends the prefix of level - 1.
            out.table[VX_MESH_TABLE_END(face, level - 1)] = out.quad_count();
        }
    }

    mesher_options options_;
    std::vector<std::uint64_t> planes_;
    std::array<std::vector<std::uint64_t>, VX_MESH_MAX_LEVEL + 1> buckets_;  // by level, 1..7
};

}  // namespace voxray::meshing
