// A triangle soup as the mesh readers produce it and the voxelizer consumes it:
// shared positions, index triples, and one group id per triangle (an OBJ 'g'/'o'
// name, or the whole file for PLY) that becomes a palette colour, unless the mesh has a
// coloured surface (io/mesh_surface.hpp), whose colours the voxels then take.
#pragma once
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "voxray/core/error.hpp"
#include "voxray/io/mesh_surface.hpp"

namespace voxray::io {

struct mesh_bounds {
    glm::dvec3 min{0.0};
    glm::dvec3 max{0.0};
    glm::dvec3 extent() const { return max - min; }
};

struct triangle_mesh {
    std::vector<glm::dvec3> positions;       // double: PLY may store doubles
    std::vector<glm::u32vec3> triangles;     // indices into positions, all in range
    std::vector<std::uint32_t> groups;       // one per triangle (or empty: all group 0)
    std::vector<std::string> group_names;    // at least one entry once a triangle exists
    mesh_surface surface;                    // materials, texture coordinates; empty: no colour

    std::size_t triangle_count() const { return triangles.size(); }

    // Throws unless every index is in range, every used position is finite and
    // groups is empty or has one entry per triangle. The readers guarantee this;
    // the voxelizer checks meshes built by hand.
    void validate() const {
        if (!groups.empty() && groups.size() != triangles.size())
            fail("mesh has ", groups.size(), " group ids for ", triangles.size(), " triangles");
        for (std::size_t t = 0; t < triangles.size(); ++t)
            for (int k = 0; k < 3; ++k) {
                auto i = triangles[t][k];
                if (i >= positions.size())
                    fail("mesh triangle ", t, " uses vertex ", i, ", but the mesh has ", positions.size(), " vertices");
                const auto& p = positions[i];
                if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
                    fail("mesh vertex ", i, " has a non-finite coordinate");
            }
        surface.validate(triangles.size());
    }

    std::uint32_t group_of(std::size_t triangle) const { return groups.empty() ? 0 : groups[triangle]; }

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
