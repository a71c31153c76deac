// The CPU mesher: one 64^3 chunk -> quads in POP order (meshing/layout.h).
//
// Per face direction:
//  1. Face masks by bitwise culling of 64-bit occupancy rows (meshing/face_planes.hpp).
//  2. Greedy merging per plane: a run of set bits with one material (and one AO pattern
//     when AO is on) is grown along the rows while the next row holds the same run. Where
//     a plane's rows run along x (Y and Z faces) the material test is one byte compare
//     per row (meshing/material_rows.hpp), not one per face.
//  3. POP order fused into emission: each quad's level (layout.h) is computed as it is made
//     and the quad goes straight into its level's bucket (meshing/pop_buckets.hpp).
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
#include "voxray/meshing/chunk.hpp"
#include "voxray/meshing/chunk_mesh.hpp"
#include "voxray/meshing/face_ao.hpp"
#include "voxray/meshing/face_planes.hpp"
#include "voxray/meshing/layout.h"
#include "voxray/meshing/material_rows.hpp"
#include "voxray/meshing/pop_buckets.hpp"

namespace voxray::meshing {

struct mesher_options {
    bool ambient_occlusion = false;  // 4 x 2 AO bits per quad; merging stops where AO differs
    bool pop_order = true;           // false: emission order, every quad in every prefix (times POP apart)
};

// The number of POP levels a quad spanning [u0, u0 + w) x [v0, v0 + h) survives: per axis
// the bit length of lo XOR hi, the smaller of the two, at most VX_MESH_MAX_LEVEL. Chunk
// origins are multiples of 64, so chunk-local coordinates give the world's answer.
inline int quad_level(int u0, int w, int v0, int h) {
    // Selects rather than std::min({...}), which may branch: on noise the levels are random.
    int along_u = std::bit_width(unsigned(u0) ^ unsigned(u0 + w)), along_v = std::bit_width(unsigned(v0) ^ unsigned(v0 + h));
    int level = along_u < along_v ? along_u : along_v;
    return level < VX_MESH_MAX_LEVEL ? level : VX_MESH_MAX_LEVEL;
}

class mesher {
public:
    explicit mesher(mesher_options options = {})
        : options_(options), planes_(chunk_edge * chunk_edge), columns_(chunk_edge * padded_edge) {}

    const mesher_options& options() const { return options_; }

    void mesh(const chunk_voxels& chunk, chunk_mesh& out) {
        out.origin = chunk.origin;
        out.words.clear();
        x_columns(chunk, columns_.data());
        for (int face = 0; face < VX_MESH_FACES; ++face) {
            face_planes(chunk, columns_.data(), face, planes_.data(), rows_used_.data());
            if (options_.ambient_occlusion) merge_face<true>(chunk, face);
            else merge_face<false>(chunk, face);
            buckets_.append_to(out, face);
        }
    }

    chunk_mesh mesh(const chunk_voxels& chunk) {
        chunk_mesh m;
        mesh(chunk, m);
        return m;
    }

private:
    template <bool AO>
    void merge_face(const chunk_voxels& c, int face) {
        switch (VX_MESH_NORMAL_AXIS(face)) {
            case 0: return merge_planes<0, AO>(c, face);
            case 1: return merge_planes<1, AO>(c, face);
            default: return merge_planes<2, AO>(c, face);
        }
    }

    // Plane coordinates (layer, row, bit) of a face with normal axis Normal -> voxel.
    template <int Normal>
    static glm::ivec3 voxel(int layer, int r, int b) {
        if constexpr (Normal == 2) return {b, r, layer};
        else if constexpr (Normal == 1) return {b, layer, r};
        else return {layer, b, r};
    }

    template <int Normal, bool AO>
    void merge_planes(const chunk_voxels& c, int face) {
        constexpr int n = chunk_edge;
        // Rows along x (Y and Z faces) compare materials a row at a time.
        constexpr bool row_compare = Normal != 0 && !AO;
        constexpr bool bits_along_u = Normal != 1;
        const std::uint8_t* material = c.material.data();
        auto material_row = [&](int layer, int r) {
            glm::ivec3 p = voxel<Normal>(layer, r, 0);
            return material + chunk_voxels::voxel_index(0, p.y, p.z);
        };
        // Occupancy of layer `front` as the planes' rows (bits along the planes' bits).
        auto front_row = [&](int front, int r) -> std::uint64_t {
            if constexpr (Normal == 2) return c.rows[chunk_voxels::row_index(r, front)];
            else if constexpr (Normal == 1) return c.rows[chunk_voxels::row_index(front, r)];
            else return columns_[std::size_t(r) * padded_edge + std::size_t(front + 1)];
        };
        const int front_step = VX_MESH_POSITIVE(face) ? 1 : -1;
        // face_ao()'s rule from three rows of the layer in front; faces in the border ring,
        // whose neighbours may lie in the shell, ask face_ao() itself.
        auto ao_bits = [&](int layer, int r, int b, glm::ivec3 p) -> std::uint32_t {
            if (r == 0 || r == n - 1 || b == 0 || b == n - 1) return face_ao(c, p, face);
            const std::uint64_t rows3[3] = {front_row(layer + front_step, r - 1), front_row(layer + front_step, r),
                                            front_row(layer + front_step, r + 1)};
            auto at = [&](int dr, int db) { return int((rows3[dr + 1] >> (b + db)) & 1u); };
            std::uint32_t bits = 0;
            for (int corner = 0; corner < 4; ++corner) {
                int du = ao_corner_du[corner], dv = ao_corner_dv[corner];
                int side_u = bits_along_u ? at(0, du) : at(du, 0), side_v = bits_along_u ? at(dv, 0) : at(0, dv);
                int diagonal = bits_along_u ? at(dv, du) : at(du, dv);
                bits |= corner_ao(side_u, side_v, diagonal) << (2 * corner);
            }
            return bits;
        };
        auto key = [&](int layer, int r, int b) -> std::uint32_t {
            glm::ivec3 p = voxel<Normal>(layer, r, b);
            std::uint32_t k = material[chunk_voxels::voxel_index(p.x, p.y, p.z)];
            if constexpr (AO) k |= ao_bits(layer, r, b, p) << 16;
            return k;
        };
        // The bits of `candidates` (consecutive, from its lowest bit) whose face has key k:
        // all of them, or the run up to the first that differs (or a subset with the same run).
        auto same_key = [&](int layer, int r, std::uint64_t candidates, std::uint32_t k) -> std::uint64_t {
            if constexpr (row_compare) {
                return candidates & same_material_mask(material_row(layer, r), std::uint8_t(k));
            } else {
                std::uint64_t same = 0;
                for (std::uint64_t bits = candidates; bits; bits &= bits - 1) {
                    int b = std::countr_zero(bits);
                    if (key(layer, r, b) != k) break;
                    same |= std::uint64_t(1) << b;
                }
                return same;
            }
        };
        auto ones = [](int count) { return count == 64 ? ~std::uint64_t(0) : ((std::uint64_t(1) << count) - 1); };
        const bool pop = options_.pop_order;
        auto emit = [&](int layer, int r, int b, int run, int rows_merged, std::uint32_t k) {
            glm::ivec3 p = voxel<Normal>(layer, r, b);
            int w = bits_along_u ? run : rows_merged, h = bits_along_u ? rows_merged : run;
            constexpr int u_axis = (Normal + 1) % 3, v_axis = (Normal + 2) % 3;
            int level = pop ? quad_level(p[u_axis], w, p[v_axis], h) : VX_MESH_MAX_LEVEL;
            std::uint32_t ao = AO ? (k >> 16) : VX_MESH_AO_OPEN;
            std::uint32_t w0 = VX_MESH_WORD0(std::uint32_t(p.x), std::uint32_t(p.y), std::uint32_t(p.z), std::uint32_t(w),
                                             std::uint32_t(h));
            std::uint32_t w1 = VX_MESH_WORD1(k & 0xFFFFu, ao, std::uint32_t(face), std::uint32_t(level));
            buckets_.push(level, std::uint64_t(w0) | (std::uint64_t(w1) << 32));
        };
        auto emit_units = [&](int layer, int r, std::uint64_t bits) {
            for (; bits; bits &= bits - 1) {
                int b = std::countr_zero(bits);
                emit(layer, r, b, 1, 1, key(layer, r, b));
            }
        };
        constexpr std::uint64_t ring_bits = 1u | (std::uint64_t(1) << 63);
        for (int layer = 0; layer < n; ++layer) {
            auto plane_at = [&](int r) -> std::uint64_t& { return planes_[plane_row(Normal, layer, r)]; };
            for (std::uint64_t pending = rows_used_[layer]; pending; pending &= pending - 1) {
                int r = std::countr_zero(pending);
                // The border ring: faces with a corner on a chunk side stay unit quads.
                if (r == 0 || r == n - 1) {
                    emit_units(layer, r, plane_at(r));
                    continue;
                }
                emit_units(layer, r, plane_at(r) & ring_bits);
                plane_at(r) &= ~ring_bits;
                while (std::uint64_t bits = plane_at(r)) {
                    int b0 = std::countr_zero(bits);
                    std::uint32_t k = key(layer, r, b0);
                    int run = std::countr_one(bits >> b0);
                    if (run > 1) run = std::countr_one(same_key(layer, r, ones(run) << b0, k) >> b0);
                    std::uint64_t span = ones(run) << b0;
                    plane_at(r) &= ~span;
                    int r2 = r + 1;
                    for (; r2 < n - 1 && (plane_at(r2) & span) == span && same_key(layer, r2, span, k) == span; ++r2)
                        plane_at(r2) &= ~span;
                    emit(layer, r, b0, run, r2 - r, k);
                }
            }
        }
    }

    mesher_options options_;
    std::vector<std::uint64_t> planes_, columns_;
    std::array<std::uint64_t, chunk_edge> rows_used_{};
    pop_buckets buckets_;
};

}  // namespace voxray::meshing
