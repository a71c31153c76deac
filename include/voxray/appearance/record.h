/* Evaluating an appearance record for a direction (issue 25), in the portable dialect: the
 * compositing walk (appearance/walk.inc) calls these for each voxel it visits, and a user's
 * shader can call them on a record it read (the installed shader includes carry this file).
 * Scalar code: uniform types only, so it runs on the CPU's scalar lanes and on the GPUs.
 * Needs prelude.h and vx_sqrt; layout.h gives the words.
 *
 * Shading is a directional light: colour * (ambient + (1 - ambient) * max(0, n . l)).
 * Colours are decoded from sRGB by a cubic (vx_app_linear8), the same on every backend; the
 * host encodes with the inverse of that same cubic, so a code decodes to the value it
 * was chosen for. Included once per lane set; no include guard on purpose. */
#include "voxray/appearance/layout.h"

/* Every function of the records and the walk returns `precise` results on GLSL: a * b + c
 * stays two roundings there, as in C++ (-ffp-contract=off) and OpenCL (FP_CONTRACT OFF),
 * which keeps the backends' pixels bit-identical. */
#define VX_APP_FN VX_FN VX_PRECISE

VX_STRUCT(vx_app_light)
    float lx, ly, lz;  /* towards the light; its length is the light reaching the voxel: 1, or
                          less where a precomputed shadow scales it (appearance/shadows.hpp) */
    float ambient;     /* 0..1 */
VX_END_STRUCT(vx_app_light)

/* A voxel's contribution along a ray: linear colour, opacity, and its normal there (unit,
 * or 0 where it has none): turned to the viewer, except where a compact record shows faces
 * seen from behind. The walk blends the normals as it blends the colours; a coarser level
 * re-sampled through the walk takes its normals from them (appearance/resample.hpp). */
VX_STRUCT(vx_app_sample)
    float r, g, b, a;
    float nx, ny, nz;
VX_END_STRUCT(vx_app_sample)

VX_APP_FN vx_app_sample vx_app_no_sample(void) {
    vx_app_sample s;
    s.r = 0.0f, s.g = 0.0f, s.b = 0.0f, s.a = 0.0f, s.nx = 0.0f, s.ny = 0.0f, s.nz = 0.0f;
    return s;
}

/* s's normal scaled to unit length, or 0 where it is 0. */
VX_APP_FN vx_app_sample vx_app_unit_normal(vx_app_sample s) {
    float length = vx_sqrt(s.nx * s.nx + s.ny * s.ny + s.nz * s.nz);
    float inv = length > 0.0f ? 1.0f / length : 0.0f;
    s.nx = s.nx * inv, s.ny = s.ny * inv, s.nz = s.nz * inv;
    return s;
}

/* An 8-bit sRGB code to linear 0..1 (layout.h). */
VX_APP_FN float vx_app_linear8(uint code) {
    float x = vx_u2f(code) * (1.0f / 255.0f);
    return VX_APP_SRGB_CUBIC(x);
}

VX_APP_FN float vx_app_snorm(uint bits, uint width) {
    uint sign_bit = 1u << (width - 1u);
    int v = vx_u2i(bits) - vx_u2i((bits & sign_bit) << 1u);
    return vx_fmax(vx_i2f(v) / vx_u2f(sign_bit - 1u), -1.0f);
}

/* An octahedral unit normal (u, v in -1..1), as (x, y, z) in `n`. */
VX_STRUCT(vx_app_vec)
    float x, y, z;
VX_END_STRUCT(vx_app_vec)

VX_APP_FN vx_app_vec vx_app_octahedral(float u, float v) {
    vx_app_vec n;
    float au = u < 0.0f ? -u : u, av = v < 0.0f ? -v : v;
    n.z = 1.0f - au - av;
    n.x = n.z < 0.0f ? (1.0f - av) * (u < 0.0f ? -1.0f : 1.0f) : u;
    n.y = n.z < 0.0f ? (1.0f - au) * (v < 0.0f ? -1.0f : 1.0f) : v;
    float inv = 1.0f / vx_sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    n.x = n.x * inv, n.y = n.y * inv, n.z = n.z * inv;
    return n;
}

VX_APP_FN float vx_app_dot(vx_app_vec a, float x, float y, float z) { return a.x * x + a.y * y + a.z * z; }

/* Opacity along unit ray direction (dx, dy, dz) from head words 1 and 2: the 13 measured
 * directions blended, each weighted by how much closer than 45 degrees it is to the ray.
 * Every direction has measured ones in reach, and an axis reads exactly its own value. (A
 * narrower reach, 35.26 degrees, would read every measured direction exactly but blends
 * worse between them: on a plane, RMS error 0.07 against 0.025 over the sphere.) */
VX_APP_FN float vx_app_opacity(uint h1, uint h2, float dx, float dy, float dz) {
    /* Blended as offsets from direction 0's value, so that equal values (a full voxel, an
     * empty one) read back exactly. */
    float base = vx_u2f(VX_APP_OPACITY_Q(h1, h2, 0u)), offsets = 0.0f, weights = 0.0f;
    for (uint k = 0u; k < VX_APP_DIRECTIONS; ++k) {
        float c = (VX_APP_DIR(k, 0u) * dx + VX_APP_DIR(k, 1u) * dy + VX_APP_DIR(k, 2u) * dz) *
                  VX_APP_DIR_INV_LENGTH(k);
        float w = vx_fmax((c < 0.0f ? -c : c) - 0.70710678f, 0.0f);
        offsets = offsets + w * (vx_u2f(VX_APP_OPACITY_Q(h1, h2, k)) - base);
        weights = weights + w;
    }
    float q = weights > 0.0f ? base + offsets / weights : base;
    return vx_fmin(vx_fmax(q * (1.0f / vx_u2f(VX_APP_OPACITY_LEVELS)), 0.0f), 1.0f);
}

/* Lambert with ambient for a normal whose dot product with the light is n_dot_l. */
VX_APP_FN float vx_app_lambert(float n_dot_l, vx_app_light light) {
    return light.ambient + (1.0f - light.ambient) * vx_fmax(n_dot_l, 0.0f);
}

/* Lambert with ambient for normal n. */
VX_APP_FN float vx_app_shade(vx_app_vec n, vx_app_light light) {
    return vx_app_lambert(vx_app_dot(n, light.lx, light.ly, light.lz), light);
}

/* The faces of a compact record along unit ray direction (dx, dy, dz): each face's colour,
 * shaded at four fixed quadrature nodes of equal weight, each node weighted by the area it
 * turns to the viewer, max(0, -m . d), and the face by its share of the surface; side -1
 * takes the normals turned round (the faces seen from behind). Returns the weighted colour
 * sum in r, g, b, the sum of the weights in a, and the faces' mean normals (as `side` turns
 * them) weighted alike in n.
 * The nodes are the face's mean normal n and three normals on a ring around it, 120 degrees
 * apart, `spread` (the ring's tangent) away: m = (n + spread (c t + s u)) / sqrt(1 + spread^2)
 * for (c, s) = (1, 0), (-1/2, +-sqrt(3)/2), in a frame (t, u) across n that comes from n alone
 * (Duff et al.'s branchless basis), so every backend gets it. A node enters only through
 * m . d and m . l, so a face takes n, t and u against d and l once, and its nodes from those. */
VX_APP_FN vx_app_sample vx_app_compact_faces(VX_BLOB faces, uint first, uint count, float dx, float dy, float dz,
                                             vx_app_light light, float side) {
    vx_app_sample sum = vx_app_no_sample();
    for (uint f = 0u; f < count; ++f) {
        uint at = (first + f) * VX_APP_FACE_WORDS;
        uint f0 = vx_load(faces, at), f1 = vx_load(faces, at + 1u);
        vx_app_vec n = vx_app_octahedral(vx_app_snorm(VX_APP_FACE_NORMAL_U(f1), 12u),
                                         vx_app_snorm(VX_APP_FACE_NORMAL_V(f1), 12u));
        float spread = vx_u2f(VX_APP_FACE_SPREAD(f1)) * (VX_APP_SPREAD_MAX / 255.0f);
        float sign = n.z < 0.0f ? -1.0f : 1.0f;
        float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
        vx_app_vec t, u;
        t.x = 1.0f + sign * n.x * n.x * a, t.y = sign * b, t.z = -sign * n.x;
        u.x = b, u.y = sign + n.y * n.y * a, u.z = -n.y;
        /* the frame against the ray and the light, turned by `side`; the ring's part scaled by spread */
        float nd = side * vx_app_dot(n, dx, dy, dz), nl = side * vx_app_dot(n, light.lx, light.ly, light.lz);
        float td = side * spread * vx_app_dot(t, dx, dy, dz);
        float tl = side * spread * vx_app_dot(t, light.lx, light.ly, light.lz);
        float ud = side * spread * vx_app_dot(u, dx, dy, dz);
        float ul = side * spread * vx_app_dot(u, light.lx, light.ly, light.lz);
        float ring = 1.0f / vx_sqrt(1.0f + spread * spread);
        float area = 0.0f, lit = 0.0f, weight = vx_u2f(VX_APP_FACE_WEIGHT(f0));
        for (uint q = 0u; q < 4u; ++q) {
            float c = q == 0u ? 0.0f : (q == 1u ? 1.0f : -0.5f);
            float s = q < 2u ? 0.0f : (q == 2u ? 0.86602540f : -0.86602540f);
            float scale = q == 0u ? 1.0f : ring;
            float md = (nd + c * td + s * ud) * scale, ml = (nl + c * tl + s * ul) * scale;
            float facing = vx_fmax(-md, 0.0f) * 0.25f;
            area = area + facing;
            lit = lit + facing * vx_app_lambert(ml, light);
        }
        /* the face's own mean normal, by the area it shows (the nodes' would lean to the viewer) */
        sum.nx = sum.nx + weight * area * side * n.x;
        sum.ny = sum.ny + weight * area * side * n.y;
        sum.nz = sum.nz + weight * area * side * n.z;
        sum.a = sum.a + weight * area;
        lit = lit * weight;
        sum.r = sum.r + lit * vx_app_linear8(VX_APP_FACE_R(f0));
        sum.g = sum.g + lit * vx_app_linear8(VX_APP_FACE_G(f0));
        sum.b = sum.b + lit * vx_app_linear8(VX_APP_FACE_B(f0));
    }
    return sum;
}

/* What a compact record shows along unit ray direction (dx, dy, dz): the colour of its faces
 * turned to the viewer (vx_app_compact_faces), and its opacity. A voxel whose faces all turn
 * away shows them turned round: it is met only where coverage leaked past the surface in
 * front of it (a closed surface seen from outside has no back to show), and there the
 * front's colour is the better guess than black. `faces` is the face pool. */
VX_APP_FN vx_app_sample vx_app_compact_sample(VX_BLOB record, VX_BLOB faces, float dx, float dy, float dz,
                                              vx_app_light light) {
    uint h0 = vx_load(record, 0u), h1 = vx_load(record, 1u), h2 = vx_load(record, 2u);
    uint first = VX_APP_FIRST_FACE(h0), count = VX_APP_FACES(h1);
    vx_app_sample got = vx_app_compact_faces(faces, first, count, dx, dy, dz, light, 1.0f);
    if (got.a <= 0.0f) {
        got = vx_app_compact_faces(faces, first, count, dx, dy, dz, light, -1.0f);
        /* the normal the faces have, away from the viewer: a re-sampling ray can tell it met
         * the surface from behind */
        got.nx = -got.nx, got.ny = -got.ny, got.nz = -got.nz;
    }
    float inv = got.a > 0.0f ? 1.0f / got.a : 0.0f;
    got.r = got.r * inv, got.g = got.g * inv, got.b = got.b * inv;
    got.a = vx_app_opacity(h1, h2, dx, dy, dz);
    return vx_app_unit_normal(got);
}

/* The colour of word w0 (r, g, b in its low three bytes) shaded with normal n turned to the
 * viewer (a record with one normal cannot tell front from back); a = 0. */
VX_APP_FN vx_app_sample vx_app_lit_word(uint w0, vx_app_vec n, float dx, float dy, float dz, vx_app_light light) {
    if (vx_app_dot(n, dx, dy, dz) > 0.0f) n.x = -n.x, n.y = -n.y, n.z = -n.z;
    float shade = vx_app_shade(n, light);
    vx_app_sample got;
    got.r = shade * vx_app_linear8(VX_APP_AVG_R(w0));
    got.g = shade * vx_app_linear8(VX_APP_AVG_G(w0));
    got.b = shade * vx_app_linear8(VX_APP_AVG_B(w0));
    got.a = 0.0f;
    got.nx = n.x, got.ny = n.y, got.nz = n.z;
    return got;
}

/* The six directions record along a ray: the words of the three axis directions the ray
 * travels along, weighted by the squares of its direction's parts (they sum to 1). Lit
 * when it was made: no light here. */
VX_APP_FN vx_app_sample vx_app_six_sample(VX_BLOB record, float dx, float dy, float dz) {
    vx_app_sample got = vx_app_no_sample();
    /* no normals stored: the faces of the axis directions it reads, weighted alike */
    got.nx = dx < 0.0f ? dx * dx : -dx * dx;
    got.ny = dy < 0.0f ? dy * dy : -dy * dy;
    got.nz = dz < 0.0f ? dz * dz : -dz * dz;
    got = vx_app_unit_normal(got);
    for (uint axis = 0u; axis < 3u; ++axis) {
        float d = axis == 0u ? dx : (axis == 1u ? dy : dz);
        uint w0 = vx_load(record, 2u * axis + (d < 0.0f ? 1u : 0u));
        float w = d * d;
        got.r = got.r + w * vx_app_linear8(VX_APP_AVG_R(w0));
        got.g = got.g + w * vx_app_linear8(VX_APP_AVG_G(w0));
        got.b = got.b + w * vx_app_linear8(VX_APP_AVG_B(w0));
        got.a = got.a + w * vx_u2f(VX_APP_AVG_OPACITY(w0)) * (1.0f / 255.0f);
    }
    return got;
}

/* exp(-t) for t >= 0 as 1 / (1 + t / 1024)^1024: ten squarings, the same on every backend
 * (within 1 % of exp for t <= 5, where it matters). */
VX_APP_FN float vx_app_exp_neg(float t) {
    float y = 1.0f + t * (1.0f / 1024.0f);
    for (uint i = 0u; i < 10u; ++i) y = y * y;
    return 1.0f / y;
}

/* The SGGX record along a ray: its opacity from the non-exponential transmittance of the
 * optical depth rho sqrt(d^T S d) / (|dx| + |dy| + |dz|); its mean colour shaded at S d, the
 * normal that the projected area leans to (the plane's normal for a plane, the view
 * direction for a sphere), turned to the viewer. */
VX_APP_FN vx_app_sample vx_app_sggx_sample(VX_BLOB record, float dx, float dy, float dz, vx_app_light light) {
    uint w0 = vx_load(record, 0u), w1 = vx_load(record, 1u), w2 = vx_load(record, 2u);
    float sx = vx_u2f(w1 & 255u) * (1.0f / 255.0f), sy = vx_u2f((w1 >> 8) & 255u) * (1.0f / 255.0f);
    float sz = vx_u2f((w1 >> 16) & 255u) * (1.0f / 255.0f);
    float rho = vx_u2f(w1 >> 24) * (VX_APP_SGGX_DENSITY_MAX / 255.0f);
    float sxy = vx_app_snorm(w2 & 255u, 8u) * sx * sy, sxz = vx_app_snorm((w2 >> 8) & 255u, 8u) * sx * sz;
    float syz = vx_app_snorm((w2 >> 16) & 255u, 8u) * sy * sz;
    vx_app_vec m; /* S d */
    m.x = sx * sx * dx + sxy * dy + sxz * dz;
    m.y = sxy * dx + sy * sy * dy + syz * dz;
    m.z = sxz * dx + syz * dy + sz * sz * dz;
    float projected = vx_sqrt(vx_fmax(vx_app_dot(m, dx, dy, dz), 0.0f));
    float chord = (dx < 0.0f ? -dx : dx) + (dy < 0.0f ? -dy : dy) + (dz < 0.0f ? -dz : dz);
    float tau = rho * projected / chord, gamma = vx_u2f(VX_APP_AVG_OPACITY(w0)) * (1.0f / 255.0f);
    float t = gamma * vx_app_exp_neg(tau) + (1.0f - gamma) * vx_fmax(1.0f - 0.5f * tau, 0.0f);
    float length = vx_sqrt(vx_app_dot(m, m.x, m.y, m.z));
    vx_app_vec n;
    n.x = 0.0f, n.y = 0.0f, n.z = 0.0f;
    if (length > 0.0f) n.x = m.x / length, n.y = m.y / length, n.z = m.z / length;
    vx_app_sample got = vx_app_lit_word(w0, n, dx, dy, dz, light);
    got.a = 1.0f - t;
    return got;
}

/* The averages record along a ray: its colour shaded with its one normal, its one opacity. */
VX_APP_FN vx_app_sample vx_app_averages_sample(VX_BLOB record, float dx, float dy, float dz, vx_app_light light) {
    uint w0 = vx_load(record, 0u), w1 = vx_load(record, 1u);
    vx_app_vec n = vx_app_octahedral(vx_app_snorm(VX_APP_AVG_NORMAL_U(w1), 16u),
                                     vx_app_snorm(VX_APP_AVG_NORMAL_V(w1), 16u));
    vx_app_sample got = vx_app_lit_word(w0, n, dx, dy, dz, light);
    got.a = vx_u2f(VX_APP_AVG_OPACITY(w0)) * (1.0f / 255.0f);
    return got;
}
