// An entity model: a voxel model as the small record every instance of it shares
// (entities/layout.h): its extent, its own min corner, an occupancy bit and a material
// byte per voxel of its box. Built once; a scene copies it into its words once.
#pragma once
#include <cstdint>
#include <vector>

#include "voxray/core/bits.hpp"
#include "voxray/core/box.hpp"
#include "voxray/core/error.hpp"
#include "voxray/entities/layout.h"
#include "voxray/model/voxel_model.hpp"

namespace voxray {

class entity_model {
public:
    explicit entity_model(const voxel_model& model) {
        bounds_ = model.bounds();
        glm::ivec3 e = bounds_.extent();
        for (int a = 0; a < 3; ++a)
            if (e[a] > VX_EM_MAX_EDGE)
                fail("entity model: the model is ", e.x, " x ", e.y, " x ", e.z, " voxels, above the limit of ",
                     VX_EM_MAX_EDGE, " on each axis (cut it into several models)");
        std::uint64_t voxels = std::uint64_t(e.x) * e.y * e.z;
        std::uint32_t bit_words = std::uint32_t((voxels + 31) / 32);
        std::uint32_t material_words = std::uint32_t((voxels + 3) / 4);
        words_.assign(VX_EM_HEADER_WORDS + bit_words + material_words, 0u);
        for (int a = 0; a < 3; ++a) {
            words_[VX_EM_EXTENT + a] = std::uint32_t(e[a]);
            words_[VX_EM_MIN + a] = std::uint32_t(bounds_.min[a]);
        }
        words_[VX_EM_BITS] = VX_EM_HEADER_WORDS;
        words_[VX_EM_MATERIALS] = VX_EM_HEADER_WORDS + bit_words;
        model.for_each_voxel([&](glm::ivec3 p, std::uint8_t value) {
            glm::uvec3 q(p - bounds_.min);
            std::uint32_t i = VX_EM_INDEX(q.x, q.y, q.z, std::uint32_t(e.x), std::uint32_t(e.y));
            bits::set(words_.data() + VX_EM_HEADER_WORDS, i);
            words_[VX_EM_HEADER_WORDS + bit_words + i / 4] |= std::uint32_t(value) << (i % 4 * 8);
        });
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

private:
    std::vector<std::uint32_t> words_;
    box3i bounds_;
    std::uint64_t voxels_ = 0;
};

}  // namespace voxray
