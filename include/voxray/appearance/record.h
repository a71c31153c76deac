/* Evaluating an appearance record for a direction (issue 25), in the portable dialect: the
 * compositing walk (appearance/walk.inc) calls these for each voxel it visits, and a user's
 * shader can call them on a record it read (the installed shader includes carry this file).
 * The compact record and what the kinds share are in compact_record.h, in lane types; the
 * baselines and the faithful helpers here are scalar code (uniform types only), for the
 * CPU's scalar lanes and the GPUs. Needs prelude.h and vx_sqrt; layout.h gives the words.
 *
 * Shading is a directional light: colour * (ambient + (1 - ambient) * max(0, n . l)).
 * Colours are decoded from sRGB by a cubic (vx_app_linear8), the same on every backend; the
 * host encodes with the inverse of that same cubic, so a code decodes to the value it
 * was chosen for. Included once per lane set; no include guard on purpose. */
#include "voxray/appearance/compact_record.h"

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
