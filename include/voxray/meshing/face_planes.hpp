// Visible faces of one direction by bitwise culling of 64-bit occupancy rows: a +Z face
// wherever a voxel is solid and the one above is not is `row(y, z) & ~row(y, z + 1)`, 64
// faces at once. The result is 64 planes (layers along the normal) of 64 rows:
//
//   Z faces: layer z, rows y, bits x      planes[layer * 64 + row]
//   Y faces: layer y, rows z, bits x      planes[row * 64 + layer]   (see plane_row)
//   X faces: layer x, rows z, bits y      planes[row * 64 + layer]
//
// so that every loop below writes consecutive words (the compiler vectorizes them).
//
//   rows_used[layer]   bit r set where row r of the layer has a face (the mesher walks
//                      only those rows)
//
// The occupancy rows run along x, the normal of X faces, so X faces are culled in columns
// along y: each z slice of the occupancy (with the x shell) transposed once per chunk
// (x_columns), which serves both X directions.
#pragma once
#include <array>
#include <cstdint>

#include "voxray/core/ray_hit_layout.h"
#include "voxray/meshing/bit_transpose.hpp"
#include "voxray/meshing/chunk.hpp"
#include "voxray/meshing/occupancy.hpp"

#if defined(__AVX2__)
#include <immintrin.h>
#endif

namespace voxray::meshing {

// Solid bits along y for x in -1..64 and z in 0..63: columns[z * 66 + x + 1], bit y.
inline void x_columns(const chunk_voxels& c, std::uint64_t* columns) {
    const int n = chunk_edge;
    std::array<std::uint64_t, chunk_edge> slice;
    for (int z = 0; z < n; ++z) {
        std::uint64_t* out = columns + z * padded_edge;
        std::uint64_t any = 0;
        const std::uint64_t* rows = c.rows.data() + chunk_voxels::row_index(0, z);
        for (int y = 0; y < n; ++y) any |= slice[y] = rows[y];
        if (any) transpose64(slice.data());
        // The x shell's bytes of this z, y = 0..63, are consecutive: one mask each.
        occupancy_rows(c.x_lo.data() + chunk_voxels::row_index(0, z), 1, out);
        occupancy_rows(c.x_hi.data() + chunk_voxels::row_index(0, z), 1, out + n + 1);
        for (int x = 0; x < n; ++x) out[x + 1] = any ? slice[x] : 0;
    }
}

// Row r of layer `layer` in the planes of a face with normal axis `normal`.
inline std::size_t plane_row(int normal, int layer, int r) {
    return normal == 2 ? std::size_t(layer) * chunk_edge + r : std::size_t(r) * chunk_edge + layer;
}

// Bit i set where words[i] is not 0, i < 64.
inline std::uint64_t nonzero_words(const std::uint64_t* words) {
    std::uint64_t mask = 0;
#if defined(__AVX2__)
    const __m256i zero = _mm256_setzero_si256();
    for (int q = 0; q < 16; ++q) {
        __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(words + 4 * q));
        int zeros = _mm256_movemask_pd(_mm256_castsi256_pd(_mm256_cmpeq_epi64(v, zero)));
        mask |= std::uint64_t(~zeros & 15) << (4 * q);
    }
#else
    for (int i = 0; i < 64; ++i) mask |= std::uint64_t(words[i] != 0) << i;
#endif
    return mask;
}

// rows_used[layer] from the planes.
inline void used_rows(int normal, const std::uint64_t* planes, std::uint64_t* rows_used) {
    const int n = chunk_edge;
    if (normal == 2) {
        for (int layer = 0; layer < n; ++layer) rows_used[layer] = nonzero_words(planes + layer * n);
        return;
    }
    for (int layer = 0; layer < n; ++layer) rows_used[layer] = 0;
    for (int r = 0; r < n; ++r)
        for (int layer = 0; layer < n; ++layer) rows_used[layer] |= std::uint64_t(planes[r * n + layer] != 0) << r;
}

// `columns`: x_columns() of the chunk, read for X faces only.
inline void face_planes(const chunk_voxels& c, const std::uint64_t* columns, int face, std::uint64_t* planes,
                        std::uint64_t* rows_used) {
    const std::uint64_t* rows = c.rows.data();
    const int n = chunk_edge;
    switch (face) {
        case VX_FACE_POS_Z:
        case VX_FACE_NEG_Z: {
            int dz = face == VX_FACE_POS_Z ? 1 : -1;
            for (int z = 0; z < n; ++z) {
                const std::uint64_t* here = rows + chunk_voxels::row_index(0, z);
                const std::uint64_t* next = rows + chunk_voxels::row_index(0, z + dz);
                for (int y = 0; y < n; ++y) planes[z * n + y] = here[y] & ~next[y];
            }
            break;
        }
        case VX_FACE_POS_Y:
        case VX_FACE_NEG_Y: {
            int dy = face == VX_FACE_POS_Y ? 1 : -1;
            for (int z = 0; z < n; ++z) {
                const std::uint64_t* here = rows + chunk_voxels::row_index(0, z);
                for (int y = 0; y < n; ++y) planes[z * n + y] = here[y] & ~here[y + dy];
            }
            break;
        }
        default: {
            int dx = face == VX_FACE_POS_X ? 1 : -1;
            for (int z = 0; z < n; ++z) {
                const std::uint64_t* column = columns + z * padded_edge + 1;
                for (int x = 0; x < n; ++x) planes[z * n + x] = column[x] & ~column[x + dx];
            }
            break;
        }
    }
    used_rows(int(VX_MESH_NORMAL_AXIS(face)), planes, rows_used);
}

}  // namespace voxray::meshing
