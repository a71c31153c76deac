// How a scene's entity pass finds the instances a ray may meet (docs/entities.md has both
// measured on the same scenes):
//   bvh          a BVH over the instances' boxes, refit as they move (instance_bvh.hpp);
//   chunk_lists  the NAADF paper's lists of instances per 16^3 chunk, walked along the ray
//                and rebuilt as instances move (chunk_lists.hpp).
#pragma once
#include <array>
#include <string_view>

#include "voxray/core/error.hpp"

namespace voxray {

enum class entity_candidates { bvh, chunk_lists };

// Every way, and the names the tool and the results use for them.
inline constexpr std::array<entity_candidates, 2> every_entity_candidates{entity_candidates::bvh,
                                                                          entity_candidates::chunk_lists};
inline constexpr std::string_view candidates_name(entity_candidates c) {
    return c == entity_candidates::bvh ? "bvh" : "chunk-lists";
}
inline entity_candidates candidates_named(std::string_view name) {
    for (entity_candidates c : every_entity_candidates)
        if (candidates_name(c) == name) return c;
    fail("entity candidates '", name, "': unknown (bvh or chunk-lists)");
}

}  // namespace voxray
