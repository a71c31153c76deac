// The model the world tests share: a terrain plus a block of noise at negative coordinates,
// so that chunks, LODs and the grid's origin all meet negative cells.
#pragma once
#include "random_models.hpp"
#include "voxray/scenes/builtin.hpp"

namespace voxray::test {

inline voxel_model world_test_model() {
    voxel_model model = scenes::make_builtin("terrain:120", 2);
    voxel_model noise = random_model(40, 0.05f, 3, glm::ivec3(-50, -20, 30));
    noise.for_each_voxel([&](glm::ivec3 p, std::uint8_t v) { model.set(p, v); });
    return model;
}

}  // namespace voxray::test
