// An entity model: a voxel model as the small record every instance of it shares
// (entities/layout.h): its extent, its own min corner, an occupancy bit and a material
// byte per voxel of its box, and a distance-field word per 4^3 brick, so a walk crosses
// empty space in a few moves. Built once; a scene copies it into its words once.
#pragma once
#include <cstdint>
#include <vector>

#include "voxray/core/bits.hpp"
#include "voxray/core/box.hpp"
#include "voxray/core/error.hpp"
#include "voxray/entities/layout.h"
#include "voxray/model/voxel_model.hpp"
#include "voxray/naadf/aadf.hpp"

namespace voxray {

// Whether a model walk crosses empty bricks by their distance fields (the default) or
// visits every voxel (`none`: slower than or level with the fields on every backend in
// docs/entities.md; kept to measure against).
enum class model_fields { bricks, none };

class entity_model {
public:
    explicit entity_model(const voxel_model& model, model_fields fields = model_fields::bricks) {
        bounds_ = model.bounds();
        glm::ivec3 e = bounds_.extent();
        for (int a = 0; a < 3; ++a)
            if (e[a] > VX_EM_MAX_EDGE)
                fail("entity model: the model is ", e.x, " x ", e.y, " x ", e.z, " voxels, above the limit of ",
                     VX_EM_MAX_EDGE, " on each axis (cut it into several models)");
        std::uint64_t voxels = std::uint64_t(e.x) * e.y * e.z;
        std::uint32_t bit_words = std::uint32_t((voxels + 31) / 32);
        std::uint32_t material_words = std::uint32_t((voxels + 3) / 4);
        glm::ivec3 nb = brick_grid(e);
        std::uint32_t brick_words = std::uint32_t(nb.x) * nb.y * nb.z;
        words_.assign(VX_EM_HEADER_WORDS + bit_words + material_words + brick_words, 0u);
        for (int a = 0; a < 3; ++a) {
            words_[VX_EM_EXTENT + a] = std::uint32_t(e[a]);
            words_[VX_EM_MIN + a] = std::uint32_t(bounds_.min[a]);
        }
        words_[VX_EM_BITS] = VX_EM_HEADER_WORDS;
        words_[VX_EM_MATERIALS] = VX_EM_HEADER_WORDS + bit_words;
        words_[VX_EM_BRICKS] = VX_EM_HEADER_WORDS + bit_words + material_words;
        std::vector<std::uint8_t> solid_bricks(brick_words, 0);
        model.for_each_voxel([&](glm::ivec3 p, std::uint8_t value) {
            glm::uvec3 q(p - bounds_.min);
            std::uint32_t i = VX_EM_INDEX(q.x, q.y, q.z, std::uint32_t(e.x), std::uint32_t(e.y));
            bits::set(words_.data() + VX_EM_HEADER_WORDS, i);
            words_[VX_EM_HEADER_WORDS + bit_words + i / 4] |= std::uint32_t(value) << (i % 4 * 8);
            glm::uvec3 b = q >> unsigned(VX_EM_BRICK_SHIFT);
            solid_bricks[b.x + nb.x * (b.y + nb.y * b.z)] = 1;
        });
        if (fields == model_fields::bricks) {
            write_brick_fields(nb, solid_bricks, words_.data() + words_[VX_EM_BRICKS]);
        } else {
            words_.resize(words_[VX_EM_BRICKS]);
            words_[VX_EM_BRICKS] = 0;
        }
        voxels_ = model.voxel_count();
    }

    const std::vector<std::uint32_t>& words() const { return words_; }
    box3i bounds() const { return bounds_; }
    glm::ivec3 extent() const { return bounds_.extent(); }
    std::uint64_t voxel_count() const { return voxels_; }

    // Whether model voxel p (the model's own coordinates) is solid, and its palette index.
    std::uint8_t get(glm::ivec3 p) const {
        if (!bounds_.contains(p)) return 0;
        glm::ivec3 e = extent();
        glm::uvec3 q(p - bounds_.min);
        std::uint32_t i = VX_EM_INDEX(q.x, q.y, q.z, std::uint32_t(e.x), std::uint32_t(e.y));
        if (!bits::test(words_.data() + VX_EM_HEADER_WORDS, i)) return 0;
        return std::uint8_t(words_[words_[VX_EM_MATERIALS] + i / 4] >> (i % 4 * 8));
    }

    bool has_fields() const { return words_[VX_EM_BRICKS] != 0; }
    // The brick field word (entities/layout.h) of brick b, from the model's min corner
    // (has_fields()).
    std::uint32_t brick_word(glm::ivec3 b) const {
        glm::ivec3 nb = brick_grid(extent());
        return words_[words_[VX_EM_BRICKS] + std::uint32_t(b.x + nb.x * (b.y + nb.y * b.z))];
    }

private:
    static glm::ivec3 brick_grid(glm::ivec3 e) { return (e + (VX_EM_BRICK_EDGE - 1)) >> VX_EM_BRICK_SHIFT; }

    // Solid bricks get the solid flag; every empty one the cuboid of empty bricks around it
    // (the NAADF builder's growth, capped at the field's 5 bits).
    static void write_brick_fields(glm::ivec3 nb, const std::vector<std::uint8_t>& solid, std::uint32_t* out) {
        naadf_detail::box_counts counts(nb, solid);
        for (int z = 0; z < nb.z; ++z)
            for (int y = 0; y < nb.y; ++y)
                for (int x = 0; x < nb.x; ++x) {
                    std::size_t i = std::size_t(x) + std::size_t(nb.x) * (y + std::size_t(nb.y) * z);
                    if (solid[i]) {
                        out[i] = VX_EM_BRICK_SOLID;
                        continue;
                    }
                    auto d = naadf_detail::grow_cuboid({x, y, z}, nb, VX_EM_FIELD_MAX,
                                                       [&](const int* lo, const int* hi) { return counts.empty(lo, hi); });
                    std::uint32_t word = 0;
                    for (std::uint32_t dir = 0; dir < 6; ++dir) word |= VX_EM_FIELD_PUT(d[dir], dir);
                    out[i] = word;
                }
    }

    std::vector<std::uint32_t> words_;
    box3i bounds_;
    std::uint64_t voxels_ = 0;
};

}  // namespace voxray
