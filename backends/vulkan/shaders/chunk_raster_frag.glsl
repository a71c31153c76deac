// Colour and identity of a chunk quad's pixel. The identity (attachment 1) is the voxel and
// face drawn there, which at level of detail 0 is what the ray tracer's primary hit
// reports for the same pixel: the voxel is the unit cell half a voxel behind the face.
layout(location = 0) in vec3 vx_world;
layout(location = 1) flat in uint vx_face_material;
layout(location = 0) out vec4 vx_colour;
layout(location = 1) out ivec4 vx_identity;  // voxel x, y, z, face (VX_FACE_*)

void main() {
    uint face = VX_MESH_FACE(vx_face_material);
    vec3 normal = vec3(0.0);
    normal[VX_MESH_NORMAL_AXIS(face)] = VX_MESH_POSITIVE(face) ? 1.0 : -1.0;
    vx_identity = ivec4(ivec3(floor(vx_world - 0.5 * normal)), int(face));
    vx_colour = vx_raster_shade(VX_MESH_MATERIAL(vx_face_material), normal);
}
