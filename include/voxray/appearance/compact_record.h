/* The compact record (layout.h) evaluated for a direction (issue 25), and what every record
 * kind shares: the light, the sample, colour and normal decoding, the opacity directions.
 * Written in lane types: one ray a lane. The GPUs, users' shaders and the CPU's scalar lanes
 * compile it as scalar code (record.h adds the other record kinds there); the CPU's SIMD
 * lanes compile it too, and evaluate a round's records 8 or 16 at once
 * (cpu/appearance_samples.hpp), bit for bit as the scalar lanes do: each lane does the same
 * operations in the same order, and lanes a loop does not need keep their values by selects.
 * Needs prelude.h and vx_sqrt; layout.h gives the words. Included once per lane set; no
 * include guard on purpose. */
#include "voxray/appearance/layout.h"

/* Every function of the records and the walk returns `precise` results on GLSL: a * b + c
 * stays two roundings there, as in C++ (-ffp-contract=off) and OpenCL (FP_CONTRACT OFF),
 * which keeps the backends' pixels bit-identical. */
#define VX_APP_FN VX_FN VX_PRECISE

VX_STRUCT(vx_app_light)
    vx_f32 lx, ly, lz;  /* towards the light; its length is the light reaching the voxel: 1, or
                           less where a precomputed shadow scales it (appearance/shadows.hpp) */
    vx_f32 ambient;     /* 0..1 */
VX_END_STRUCT(vx_app_light)

/* A voxel's contribution along a ray: linear colour, opacity, and its normal there (unit,
 * or 0 where it has none): turned to the viewer, except where a compact record shows faces
 * seen from behind. The walk blends the normals as it blends the colours; a coarser level
 * re-sampled through the walk takes its normals from them (appearance/resample.hpp). */
VX_STRUCT(vx_app_sample)
    vx_f32 r, g, b, a;
    vx_f32 nx, ny, nz;
VX_END_STRUCT(vx_app_sample)

VX_APP_FN vx_app_sample vx_app_no_sample(void) {
    vx_app_sample s;
    vx_f32 zero = vx_f32_splat(0.0f);
    s.r = zero, s.g = zero, s.b = zero, s.a = zero, s.nx = zero, s.ny = zero, s.nz = zero;
    return s;
}

/* s's normal scaled to unit length, or 0 where it is 0. */
VX_APP_FN vx_app_sample vx_app_unit_normal(vx_app_sample s) {
    vx_f32 length = vx_sqrt(s.nx * s.nx + s.ny * s.ny + s.nz * s.nz);
    vx_f32 inv = vx_sel(length > 0.0f, 1.0f / length, vx_f32_splat(0.0f));
    s.nx = s.nx * inv, s.ny = s.ny * inv, s.nz = s.nz * inv;
    return s;
}

/* An 8-bit sRGB code to linear 0..1 (layout.h). */
VX_APP_FN vx_f32 vx_app_linear8(vx_u32 code) {
    vx_f32 x = vx_u2f(code) * (1.0f / 255.0f);
    return VX_APP_SRGB_CUBIC(x);
}

VX_APP_FN vx_f32 vx_app_snorm(vx_u32 bits, uint width) {
    uint sign_bit = 1u << (width - 1u);
    vx_i32 v = vx_u2i(bits) - vx_u2i((bits & sign_bit) << 1u);
    return vx_fmax(vx_i2f(v) / vx_u2f(sign_bit - 1u), -1.0f);
}

/* An octahedral unit normal (u, v in -1..1), as (x, y, z) in `n`. */
VX_STRUCT(vx_app_vec)
    vx_f32 x, y, z;
VX_END_STRUCT(vx_app_vec)

VX_APP_FN vx_app_vec vx_app_octahedral(vx_f32 u, vx_f32 v) {
    vx_app_vec n;
    vx_f32 au = vx_sel(u < 0.0f, -u, u), av = vx_sel(v < 0.0f, -v, v);
    vx_f32 su = vx_sel(u < 0.0f, vx_f32_splat(-1.0f), vx_f32_splat(1.0f));
    vx_f32 sv = vx_sel(v < 0.0f, vx_f32_splat(-1.0f), vx_f32_splat(1.0f));
    n.z = 1.0f - au - av;
    n.x = vx_sel(n.z < 0.0f, (1.0f - av) * su, u);
    n.y = vx_sel(n.z < 0.0f, (1.0f - au) * sv, v);
    vx_f32 inv = 1.0f / vx_sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
    n.x = n.x * inv, n.y = n.y * inv, n.z = n.z * inv;
    return n;
}

VX_APP_FN vx_f32 vx_app_dot(vx_app_vec a, vx_f32 x, vx_f32 y, vx_f32 z) { return a.x * x + a.y * y + a.z * z; }

/* Opacity along unit ray direction (dx, dy, dz) from head words 1 and 2: the 13 measured
 * directions blended, each weighted by how much closer than 45 degrees it is to the ray.
 * Every direction has measured ones in reach, and an axis reads exactly its own value. (A
 * narrower reach, 35.26 degrees, would read every measured direction exactly but blends
 * worse between them: on a plane, RMS error 0.07 against 0.025 over the sphere.) */
VX_APP_FN vx_f32 vx_app_opacity(vx_u32 h1, vx_u32 h2, vx_f32 dx, vx_f32 dy, vx_f32 dz) {
    /* Blended as offsets from direction 0's value, so that equal values (a full voxel, an
     * empty one) read back exactly. */
    vx_f32 base = vx_u2f(VX_APP_OPACITY_Q(h1, h2, 0u)), offsets = vx_f32_splat(0.0f), weights = offsets;
    for (uint k = 0u; k < VX_APP_DIRECTIONS; ++k) {
        vx_f32 c = (VX_APP_DIR(k, 0u) * dx + VX_APP_DIR(k, 1u) * dy + VX_APP_DIR(k, 2u) * dz) *
                   VX_APP_DIR_INV_LENGTH(k);
        vx_f32 w = vx_fmax(vx_sel(c < 0.0f, -c, c) - 0.70710678f, 0.0f);
        offsets = offsets + w * (vx_u2f(VX_APP_OPACITY_Q(h1, h2, k)) - base);
        weights = weights + w;
    }
    vx_f32 q = vx_sel(weights > 0.0f, base + offsets / weights, base);
    return vx_fmin(vx_fmax(q * (1.0f / vx_u2f(VX_APP_OPACITY_LEVELS)), 0.0f), 1.0f);
}

/* Lambert with ambient for a normal whose dot product with the light is n_dot_l. */
VX_APP_FN vx_f32 vx_app_lambert(vx_f32 n_dot_l, vx_app_light light) {
    return light.ambient + (1.0f - light.ambient) * vx_fmax(n_dot_l, 0.0f);
}

/* Lambert with ambient for normal n. */
VX_APP_FN vx_f32 vx_app_shade(vx_app_vec n, vx_app_light light) {
    return vx_app_lambert(vx_app_dot(n, light.lx, light.ly, light.lz), light);
}

/* A compact record's face, decoded (face words f0, f1): its mean normal n, a frame (t, u)
 * across it that comes from n alone (Duff et al.'s branchless basis, so every backend gets
 * it), its ring's spread (the tangent of its angle) and 1 / sqrt(1 + spread^2), its share of
 * the surface and its linear colour. */
VX_STRUCT(vx_app_face)
    vx_app_vec n, t, u;
    vx_f32 spread, ring, weight, r, g, b;
VX_END_STRUCT(vx_app_face)

VX_APP_FN vx_app_face vx_app_decode_face(vx_u32 f0, vx_u32 f1) {
    vx_app_face face;
    face.n = vx_app_octahedral(vx_app_snorm(VX_APP_FACE_NORMAL_U(f1), 12u),
                               vx_app_snorm(VX_APP_FACE_NORMAL_V(f1), 12u));
    face.spread = vx_u2f(VX_APP_FACE_SPREAD(f1)) * (VX_APP_SPREAD_MAX / 255.0f);
    vx_app_vec n = face.n;
    vx_f32 sign = vx_sel(n.z < 0.0f, vx_f32_splat(-1.0f), vx_f32_splat(1.0f));
    vx_f32 a = -1.0f / (sign + n.z), b = n.x * n.y * a;
    face.t.x = 1.0f + sign * n.x * n.x * a, face.t.y = sign * b, face.t.z = -sign * n.x;
    face.u.x = b, face.u.y = sign + n.y * n.y * a, face.u.z = -n.y;
    face.ring = 1.0f / vx_sqrt(1.0f + face.spread * face.spread);
    face.weight = vx_u2f(VX_APP_FACE_WEIGHT(f0));
    face.r = vx_app_linear8(VX_APP_FACE_R(f0)), face.g = vx_app_linear8(VX_APP_FACE_G(f0));
    face.b = vx_app_linear8(VX_APP_FACE_B(f0));
    return face;
}

/* `sum` plus what `face` shows along unit ray direction (dx, dy, dz) in the lanes of `on`:
 * its colour, shaded at four fixed quadrature nodes of equal weight, each node weighted by
 * the area it turns to the viewer, max(0, -m . d), and the face by its share of the surface;
 * side -1 takes the normals turned round (the face seen from behind). Adds the weighted
 * colour to r, g, b, the weight to a, and the face's mean normal (as `side` turns it)
 * weighted alike to n. The nodes are n and three normals on a ring around it, 120 degrees
 * apart: m = (n + spread (c t + s u)) / sqrt(1 + spread^2) for (c, s) = (1, 0),
 * (-1/2, +-sqrt(3)/2). A node enters only through m . d and m . l, so the face takes n, t and
 * u against d and l once, and its nodes from those. */
VX_APP_FN vx_app_sample vx_app_face_seen(vx_app_sample sum, vx_app_face face, vx_f32 dx, vx_f32 dy, vx_f32 dz,
                                         vx_app_light light, float side, vx_mask on) {
    /* the frame against the ray and the light, turned by `side`; the ring's part scaled by spread */
    vx_f32 nd = side * vx_app_dot(face.n, dx, dy, dz), nl = side * vx_app_dot(face.n, light.lx, light.ly, light.lz);
    vx_f32 td = side * face.spread * vx_app_dot(face.t, dx, dy, dz);
    vx_f32 tl = side * face.spread * vx_app_dot(face.t, light.lx, light.ly, light.lz);
    vx_f32 ud = side * face.spread * vx_app_dot(face.u, dx, dy, dz);
    vx_f32 ul = side * face.spread * vx_app_dot(face.u, light.lx, light.ly, light.lz);
    vx_f32 area = vx_f32_splat(0.0f), lit = area;
    for (uint q = 0u; q < 4u; ++q) {
        float c = q == 0u ? 0.0f : (q == 1u ? 1.0f : -0.5f);
        float s = q < 2u ? 0.0f : (q == 2u ? 0.86602540f : -0.86602540f);
        vx_f32 scale = q == 0u ? vx_f32_splat(1.0f) : face.ring;
        vx_f32 md = (nd + c * td + s * ud) * scale, ml = (nl + c * tl + s * ul) * scale;
        vx_f32 facing = vx_fmax(-md, 0.0f) * 0.25f;
        area = area + facing;
        lit = lit + facing * vx_app_lambert(ml, light);
    }
    /* the face's own mean normal, by the area it shows (the nodes' would lean to the viewer) */
    vx_f32 weight = face.weight;
    sum.nx = vx_sel(on, sum.nx + weight * area * side * face.n.x, sum.nx);
    sum.ny = vx_sel(on, sum.ny + weight * area * side * face.n.y, sum.ny);
    sum.nz = vx_sel(on, sum.nz + weight * area * side * face.n.z, sum.nz);
    sum.a = vx_sel(on, sum.a + weight * area, sum.a);
    lit = lit * weight;
    sum.r = vx_sel(on, sum.r + lit * face.r, sum.r);
    sum.g = vx_sel(on, sum.g + lit * face.g, sum.g);
    sum.b = vx_sel(on, sum.b + lit * face.b, sum.b);
    return sum;
}

/* The faces of a compact record along unit ray direction (dx, dy, dz), in the lanes of
 * `lanes`, seen from the front (`front`) and turned round (`back`, every face as if from
 * behind): vx_app_face_seen summed over the faces, each face decoded once for both. */
VX_STRUCT(vx_app_faces_seen)
    vx_app_sample front, back;
VX_END_STRUCT(vx_app_faces_seen)

VX_APP_FN vx_app_faces_seen vx_app_compact_faces(VX_BLOB faces, vx_u32 first, vx_u32 count, vx_f32 dx, vx_f32 dy,
                                                 vx_f32 dz, vx_app_light light, vx_mask lanes) {
    vx_app_faces_seen seen;
    seen.front = vx_app_no_sample(), seen.back = vx_app_no_sample();
    for (uint f = 0u; vx_any(lanes && count > f); ++f) {
        vx_mask on = lanes && count > f;  /* the lanes whose record has face f */
        vx_u32 at = (first + f) * VX_APP_FACE_WORDS;
        vx_app_face face = vx_app_decode_face(vx_gather_masked(faces, on, at), vx_gather_masked(faces, on, at + 1u));
        seen.front = vx_app_face_seen(seen.front, face, dx, dy, dz, light, 1.0f, on);
        seen.back = vx_app_face_seen(seen.back, face, dx, dy, dz, light, -1.0f, on);
    }
    return seen;
}

/* What record `row` of a compact table shows along unit ray direction (dx, dy, dz): the
 * colour of its faces turned to the viewer (vx_app_compact_faces), and its opacity. A voxel
 * whose faces all turn away shows them turned round: it is met only where coverage leaked
 * past the surface in front of it (a closed surface seen from outside has no back to show),
 * and there the front's colour is the better guess than black. `faces` is the face pool. */
VX_APP_FN vx_app_sample vx_app_compact_sample(VX_BLOB records, VX_BLOB faces, vx_u32 row, vx_f32 dx, vx_f32 dy,
                                              vx_f32 dz, vx_app_light light) {
    vx_u32 at = row * VX_APP_COMPACT_WORDS;
    vx_u32 h0 = vx_gather(records, at), h1 = vx_gather(records, at + 1u), h2 = vx_gather(records, at + 2u);
    vx_u32 first = VX_APP_FIRST_FACE(h0), count = VX_APP_FACES(h1);
    vx_app_faces_seen seen = vx_app_compact_faces(faces, first, count, dx, dy, dz, light, count > 0u);
    vx_app_sample got = seen.front, turned = seen.back;
    vx_mask back = got.a <= 0.0f;
    /* the normal the faces have, away from the viewer: a re-sampling ray can tell it met the
     * surface from behind */
    got.r = vx_sel(back, turned.r, got.r), got.g = vx_sel(back, turned.g, got.g);
    got.b = vx_sel(back, turned.b, got.b), got.a = vx_sel(back, turned.a, got.a);
    got.nx = vx_sel(back, -turned.nx, got.nx), got.ny = vx_sel(back, -turned.ny, got.ny);
    got.nz = vx_sel(back, -turned.nz, got.nz);
    vx_f32 inv = vx_sel(got.a > 0.0f, 1.0f / got.a, vx_f32_splat(0.0f));
    got.r = got.r * inv, got.g = got.g * inv, got.b = got.b * inv;
    got.a = vx_app_opacity(h1, h2, dx, dy, dz);
    return vx_app_unit_normal(got);
}
