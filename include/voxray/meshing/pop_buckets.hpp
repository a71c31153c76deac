// POP order fused into emission: the mesher drops each quad into its level's bucket as it
// makes it (one store through a cursor, no size checks: each bucket holds a face's worst
// case, 64^3 / 2 quads), and a finished face is appended coarse to fine with its prefixes
// written into the table (meshing/layout.h).
#pragma once
#include <bit>
#include <cstdint>
#include <cstring>
#include <memory>

#include "voxray/meshing/chunk_mesh.hpp"
#include "voxray/meshing/layout.h"

namespace voxray::meshing {

class pop_buckets {
public:
    // The most quads one face direction of a 64^3 chunk can have (a 3-D checkerboard).
    static constexpr std::size_t face_capacity = std::size_t(VX_MESH_CHUNK_EDGE) * VX_MESH_CHUNK_EDGE * VX_MESH_CHUNK_EDGE / 2;

    pop_buckets() : storage_(new std::uint64_t[stride * VX_MESH_MAX_LEVEL]) { reset(); }
    pop_buckets(const pop_buckets&) : pop_buckets() {}  // scratch: a copy starts empty
    pop_buckets& operator=(const pop_buckets&) { return *this; }

    void reset() {
        for (int level = 1; level <= VX_MESH_MAX_LEVEL; ++level) cursor_[level] = begin(level);
    }
    void push(int level, std::uint64_t quad) { *cursor_[level]++ = quad; }

    // Appends the buckets as face `face`'s quads, coarse to fine, and empties them.
    void append_to(chunk_mesh& out, int face) {
        std::size_t total = 0;
        for (int level = 1; level <= VX_MESH_MAX_LEVEL; ++level) total += std::size_t(cursor_[level] - begin(level));
        std::size_t at = out.words.size();
        out.words.resize(at + total * VX_MESH_QUAD_WORDS);
        for (int level = VX_MESH_MAX_LEVEL; level >= 1; --level) {
            std::size_t n = std::size_t(cursor_[level] - begin(level));
            if (n) std::memcpy(out.words.data() + at, begin(level), n * sizeof(std::uint64_t));  // word 0 low: little endian
            at += n * VX_MESH_QUAD_WORDS;
            // Drawn at level of detail i while i < level: this bucket ends the prefix of level - 1.
            out.table[VX_MESH_TABLE_END(face, level - 1)] = std::uint32_t(at / VX_MESH_QUAD_WORDS);
        }
        reset();
    }

private:
    // Buckets 1 MiB apart would share cache sets; 4160 bytes more keeps their ends apart.
    static constexpr std::size_t stride = face_capacity + 520;
    std::uint64_t* begin(int level) const { return storage_.get() + std::size_t(level - 1) * stride; }

    std::unique_ptr<std::uint64_t[]> storage_;
    std::uint64_t* cursor_[VX_MESH_MAX_LEVEL + 1] = {};
};

static_assert(std::endian::native == std::endian::little, "pop_buckets stores a quad's two words as one little-endian 64-bit value");

}  // namespace voxray::meshing
