// The order of integer positions (chunk origins, cells) z first, then y, then x: the order
// in which the grids and chunk lists of the library are walked, for sorting and std::map.
#pragma once
#include <tuple>

#include <glm/vec3.hpp>

namespace voxray {

struct ivec3_less {
    bool operator()(glm::ivec3 a, glm::ivec3 b) const { return std::tie(a.z, a.y, a.x) < std::tie(b.z, b.y, b.x); }
};

}  // namespace voxray
