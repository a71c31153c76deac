// The vertex side of POP meshes (meshing/pop.h) on the host: the reference the crack tests
// and the tool use, from the very source the shaders compile.
#pragma once
#include <algorithm>
#include <cmath>
#include <cstdint>

#include <glm/vec3.hpp>

#include "voxray/kernels/prelude.h"

namespace voxray::meshing {

namespace pop_scalar {
using vx_f32 = float;
using vx_i32 = std::int32_t;
using vx_u32 = std::uint32_t;
inline float vx_floor(float x) { return std::floor(x); }
inline float vx_log2(float x) { return std::log2(x); }
inline float vx_i2f(std::int32_t x) { return float(x); }
inline std::int32_t vx_f2i(float x) { return std::int32_t(x); }
inline std::int32_t vx_u2i(std::uint32_t x) { return std::int32_t(x); }
inline float vx_fmin(float a, float b) { return a < b ? a : b; }
inline float vx_fmax(float a, float b) { return a > b ? a : b; }
#include "voxray/meshing/pop.h"
}  // namespace pop_scalar

// Where the camera is and how fast detail falls off: t = log2(distance) - bias.
struct pop_view {
    glm::vec3 eye{0.0f};
    float bias = 0.0f;
};

inline float pop_lod(glm::ivec3 vertex, const pop_view& view) {
    return pop_scalar::vx_pop_stable_lod(vertex.x, vertex.y, vertex.z, view.eye.x, view.eye.y, view.eye.z, view.bias);
}

inline glm::vec3 pop_vertex(glm::ivec3 vertex, const pop_view& view) {
    glm::vec3 p;
    pop_scalar::vx_pop_vertex(vertex.x, vertex.y, vertex.z, view.eye.x, view.eye.y, view.eye.z, view.bias, p.x, p.y, p.z);
    return p;
}

inline glm::ivec3 quad_corner(std::uint32_t w0, std::uint32_t w1, int corner, glm::ivec3 origin) {
    glm::ivec3 p;
    pop_scalar::vx_mesh_corner(w0, w1, std::uint32_t(corner), origin.x, origin.y, origin.z, p.x, p.y, p.z);
    return p;
}

// The level of detail whose prefix a chunk draws: every quad must be there that is not yet
// degenerate at the smallest t any of its vertices takes. t is one value per cell of the
// chunk grid, so the smallest is over the 27 cells of the chunk's closed box.
inline int chunk_draw_level(glm::ivec3 origin, const pop_view& view) {
    float smallest = float(VX_POP_TOP_LEVEL);
    for (int k = 0; k < 27; ++k) {
        glm::ivec3 step{k % 3, (k / 3) % 3, k / 9};  // 0: low side, 1: inside, 2: high side
        glm::ivec3 p = origin + step * (VX_MESH_CHUNK_EDGE / 2);
        smallest = std::min(smallest, pop_lod(p, view));
    }
    return int(std::floor(smallest));
}

}  // namespace voxray::meshing
