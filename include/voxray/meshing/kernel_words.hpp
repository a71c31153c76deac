// The mesher kernel's buffers on the host (meshing/kernel_layout.h): chunks packed into the
// words the kernel reads, the frame header it starts from, and its quads read back as
// chunk meshes. Used by meshing/kernel_mesher.hpp on every backend.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "voxray/core/error.hpp"
#include "voxray/meshing/chunk.hpp"
#include "voxray/meshing/chunk_mesh.hpp"
#include "voxray/meshing/kernel_layout.h"

namespace voxray::meshing {

// The most quads a 64^3 chunk has (a 3-D checkerboard: every face of half the voxels).
inline constexpr std::uint32_t most_chunk_quads = 64u * 64u * 64u / 2u * VX_MESH_FACES;

// Writes chunk `c` as the kernel's input words (VX_MK_CHUNK_WORDS of them) at `out`.
inline void pack_chunk_words(const chunk_voxels& c, std::uint32_t* out) {
    for (std::size_t r = 0; r < c.rows.size(); ++r) {
        out[VX_MK_ROWS + 2 * r] = std::uint32_t(c.rows[r]);
        out[VX_MK_ROWS + 2 * r + 1] = std::uint32_t(c.rows[r] >> 32);
    }
    for (std::uint32_t w = 0; w < 2 * VX_MK_SHELL_WORDS; ++w) out[VX_MK_X_LOW + w] = 0;
    for (std::size_t r = 0; r < c.x_lo.size(); ++r) {
        if (c.x_lo[r]) out[VX_MK_X_LOW + r / 32] |= 1u << (r % 32);
        if (c.x_hi[r]) out[VX_MK_X_HIGH + r / 32] |= 1u << (r % 32);
    }
    for (std::size_t i = 0; i < c.material.size(); i += 4)
        out[VX_MK_MATERIALS + i / 4] = std::uint32_t(c.material[i]) | std::uint32_t(c.material[i + 1]) << 8 |
                                       std::uint32_t(c.material[i + 2]) << 16 | std::uint32_t(c.material[i + 3]) << 24;
}

inline std::vector<std::uint32_t> pack_chunks_words(std::span<const chunk_voxels> chunks) {
    // The kernel indexes its input with 32-bit words.
    std::uint64_t words = std::uint64_t(chunks.size()) * VX_MK_CHUNK_WORDS;
    if (words > 0xFFFFFFFFull)
        fail("mesher kernel: ", chunks.size(), " chunks are ", words, " input words, over the kernel's 2^32; ",
             "mesh at most ", 0xFFFFFFFFull / VX_MK_CHUNK_WORDS, " chunks at a time");
    std::vector<std::uint32_t> out(words);
    for (std::size_t i = 0; i < chunks.size(); ++i) pack_chunk_words(chunks[i], out.data() + i * VX_MK_CHUNK_WORDS);
    return out;
}

// Where the kernel's words for `chunks` chunks of at most `capacity` quads each go.
struct kernel_frame {
    std::uint64_t chunks = 0, capacity = 0;

    std::uint64_t block_words() const { return VX_MK_BLOCK_WORDS(capacity); }
    std::uint64_t block(std::uint64_t chunk) const { return VX_MK_HEADER_WORDS + chunk * block_words(); }
    std::uint64_t words() const { return block(chunks); }

    // Refuses a frame the kernel's 32-bit indices cannot reach, with the numbers.
    void check() const {
        if (capacity > most_chunk_quads)
            fail("mesher kernel: a capacity of ", capacity, " quads a chunk is more than any chunk has (",
                 most_chunk_quads, ")");
        if (words() > 0xFFFFFFFFull)
            fail("mesher kernel: ", chunks, " chunks of up to ", capacity, " quads need ", words(),
                 " frame words, over the kernel's 2^32; mesh fewer chunks at a time or lower the capacity");
    }

    std::vector<std::uint32_t> header(std::uint32_t flags) const {
        std::vector<std::uint32_t> h(VX_MK_HEADER_WORDS, 0);
        h[VX_MK_HEADER_CHUNKS] = std::uint32_t(chunks);
        h[VX_MK_HEADER_FLAGS] = flags;
        h[VX_MK_HEADER_CAPACITY] = std::uint32_t(capacity);
        return h;
    }
};

}  // namespace voxray::meshing
