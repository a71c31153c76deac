// Indexed triangles by vertex pulling (positions and indices by device address, a
// non-indexed draw of 3 vertices a triangle): the meshes of other tools drawn beside chunk
// meshes with the same camera and light, such as meshoptimizer's simplifications of them.
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer vx_raster_floats { float f[]; };
layout(buffer_reference, std430, buffer_reference_align = 4) readonly buffer vx_raster_indices { uint i[]; };

layout(location = 0) out vec3 vx_world;

void main() {
    uint v = vx_raster_indices(frame.data[1]).i[gl_VertexIndex];
    vx_raster_floats p = vx_raster_floats(frame.data[0]);
    vx_world = vec3(p.f[3u * v], p.f[3u * v + 1u], p.f[3u * v + 2u]);
    gl_Position = frame.view_projection * vec4(vx_world - frame.eye_and_bias.xyz, 1.0);
}
