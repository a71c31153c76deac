// A triangle's pixel: the one colour lit by the triangle's own plane (from the position's
// screen derivatives, turned towards the eye); its identity says "a surface, no voxel".
layout(location = 0) in vec3 vx_world;
layout(location = 0) out vec4 vx_colour;
layout(location = 1) out ivec4 vx_identity;

void main() {
    vec3 normal = normalize(cross(dFdx(vx_world), dFdy(vx_world)));
    if (dot(normal, frame.eye_and_bias.xyz - vx_world) < 0.0) normal = -normal;
    vx_identity = ivec4(0, 0, 0, int(VX_FACE_INSIDE));
    vx_colour = vx_raster_shade(0u, normal);
}
