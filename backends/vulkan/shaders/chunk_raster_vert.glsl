// Vertex pulling of POP chunk quads: six vertices a quad, no vertex buffer. A draw is one
// face direction of one chunk at its level of detail (a prefix of that face's quads); its
// first instance is the chunk's index, which finds the chunk's placement. The corner comes
// from meshing/pop.h's vx_mesh_corner and the morph from vx_pop_vertex, the sources the
// CPU reference compiles too.
//
// A chunk's placement is two ivec4s: its origin in its own cells and the cell size as a
// shift (0 for voxels), then the world position of cell (0, 0, 0). The quads are rounded
// and morphed in cells, with the eye brought into the same units, and then placed in the
// world: a chunk of an open world's LOD n has cells of 2^n voxels.
layout(buffer_reference, std430, buffer_reference_align = 8) readonly buffer vx_raster_quads { uvec2 q[]; };
layout(buffer_reference, std430, buffer_reference_align = 16) readonly buffer vx_raster_placements { ivec4 o[]; };

layout(location = 0) out vec3 vx_world;              // the morphed position
layout(location = 1) flat out uint vx_face_material;  // the quad's word 1

void main() {
    // Both triangles counter-clockwise seen from outside the face: the corners run u, then
    // v (layout.h), and u x v is +normal, so a negative face takes them the other way round.
    const uint positive_order[6] = uint[6](0u, 1u, 2u, 0u, 2u, 3u);
    const uint negative_order[6] = uint[6](0u, 2u, 1u, 0u, 3u, 2u);
    uint quad = uint(gl_VertexIndex) / 6u, slot = uint(gl_VertexIndex) % 6u;
    uvec2 q = vx_raster_quads(frame.data[0]).q[quad];
    vx_raster_placements placements = vx_raster_placements(frame.data[1]);
    ivec4 cells = placements.o[2 * gl_InstanceIndex], world = placements.o[2 * gl_InstanceIndex + 1];
    uint corner = VX_MESH_POSITIVE(VX_MESH_FACE(q.y)) ? positive_order[slot] : negative_order[slot];
    int x, y, z;
    vx_mesh_corner(q.x, q.y, corner, cells.x, cells.y, cells.z, x, y, z);
    float cell = float(1 << cells.w);
    vec4 eb = frame.eye_and_bias;
    vec3 eye = (eb.xyz - vec3(world.xyz)) / cell;
    vec3 p;
    if (frame.fixed_level == VX_RASTER_BY_DISTANCE) {
        vx_pop_vertex(x, y, z, eye.x, eye.y, eye.z, eb.w, p.x, p.y, p.z);
    } else {
        int level = int(frame.fixed_level);
        p = vec3(float(vx_pop_round(x, level)), float(vx_pop_round(y, level)), float(vx_pop_round(z, level)));
    }
    vx_world = vec3(world.xyz) + p * cell;
    // Relative to the eye before the projection: world coordinates of thousands keep
    // their precision where it matters, near the camera.
    gl_Position = frame.view_projection * vec4(vx_world - eb.xyz, 1.0);
    vx_face_material = q.y;
}
