// A triangle soup as the mesh readers produce it and the voxelizer consumes it:
// shared positions, index triples, and one group id per triangle (an OBJ 'g'/'o'
// name, or the whole file for PLY) that becomes a palette colour.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

namespace voxray::io {

struct mesh_bounds {
    glm::dvec3 min{0.0};
    glm::dvec3 max{0.0};
    glm::dvec3 extent() const { return max - min; }
};

struct triangle_mesh {
    std::vector<glm::dvec3> positions;       // double: PLY may store doubles
    std::vector<glm::u32vec3> triangles;     // indices into positions, all in range
    std::vector<std::uint32_t> groups;       // one per triangle, index into group_names
    std::vector<std::string> group_names;    // at least one entry once a triangle exists

    std::size_t triangle_count() const { return triangles.size(); }

    // Bounds of the vertices that triangles use (unused vertices do not count, so
    // a stray 'v' line far away cannot shrink the voxelized object).
    mesh_bounds bounds() const {
        mesh_bounds b;
        if (triangles.empty()) return b;
        b.min = b.max = positions[triangles[0].x];
        for (auto& t : triangles)
            for (int k = 0; k < 3; ++k) {
                const auto& p = positions[t[k]];
                b.min = glm::min(b.min, p);
                b.max = glm::max(b.max, p);
            }
        return b;
    }
};

}  // namespace voxray::io
