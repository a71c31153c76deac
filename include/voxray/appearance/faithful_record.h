/* Evaluating a *faithful* record (layout.h) for a direction as the paper does (its sections
 * 3.3 and 3.4), in the portable dialect: the colour by projected-area sampling of the virtual
 * octahedron, the opacity by the subgrid's spheres drawn on a 4 x 4 window. Two departures,
 * for bit-identical results on every backend: 16 fixed points a face (the centroids of its 16
 * sub-triangles) in place of up to 40 random ones, and an acos made of +, *, / and sqrt.
 * Needs record.h before it. Included once per lane set; no include guard on purpose. */

/* A frame or face word's three snorm8 components, as a unit vector (0 for a zero word). */
VX_APP_FN vx_app_vec vx_app_byte_vec(uint w) {
    vx_app_vec v;
    v.x = vx_app_snorm(VX_APP_BYTE(w, 0u), 8u), v.y = vx_app_snorm(VX_APP_BYTE(w, 1u), 8u);
    v.z = vx_app_snorm(VX_APP_BYTE(w, 2u), 8u);
    float length = vx_sqrt(v.x * v.x + v.y * v.y + v.z * v.z);
    float inv = length > 0.0f ? 1.0f / length : 0.0f;
    v.x = v.x * inv, v.y = v.y * inv, v.z = v.z * inv;
    return v;
}

/* acos of x in -1..1 (clamped), within 7e-5 rad (Abramowitz and Stegun 4.4.45). */
VX_APP_FN float vx_app_acos(float x) {
    float a = vx_fmin(x < 0.0f ? -x : x, 1.0f);
    float r = vx_sqrt(1.0f - a) * (1.5707288f + a * (-0.2121144f + a * (0.0742610f - 0.0187293f * a)));
    return x < 0.0f ? 3.14159265f - r : r;
}

/* The area two disks of radii r1 and r2 share when their centres are d apart. */
VX_APP_FN float vx_app_lens_area(float d, float r1, float r2) {
    float small = vx_fmin(r1, r2), big = vx_fmax(r1, r2);
    if (d >= r1 + r2) return 0.0f;
    if (d <= big - small) return 3.14159265f * small * small;
    float a1 = vx_app_acos((d * d + r1 * r1 - r2 * r2) / (2.0f * d * r1));
    float a2 = vx_app_acos((d * d + r2 * r2 - r1 * r1) / (2.0f * d * r2));
    float k = (r1 + r2 - d) * (d + r1 - r2) * (d - r1 + r2) * (d + r1 + r2);
    return r1 * r1 * a1 + r2 * r2 * a2 - 0.5f * vx_sqrt(vx_fmax(k, 0.0f));
}

/* The paper's directional opacity along unit direction d: a square window that bounds the
 * voxel's parallel projection, cut into 4 x 4 pixels; each of the 27 subgrid elements drawn
 * as the disk of its enclosing sphere; each pixel keeps the largest opacity x the share of its
 * inscribed circle that a disk covers; the voxel's opacity is the pixels' mean. */
VX_APP_FN float vx_app_faithful_opacity(VX_BLOB record, float dx, float dy, float dz) {
    float sign = dz < 0.0f ? -1.0f : 1.0f;  /* a frame (u, w) across d, as vx_app_face_node's */
    float a = -1.0f / (sign + dz), b = dx * dy * a;
    vx_app_vec u, w;
    u.x = 1.0f + sign * dx * dx * a, u.y = sign * b, u.z = -sign * dx;
    w.x = b, w.y = sign + dy * dy * a, w.z = -dy;
    float hu = (u.x < 0.0f ? -u.x : u.x) + (u.y < 0.0f ? -u.y : u.y) + (u.z < 0.0f ? -u.z : u.z);
    float hw = (w.x < 0.0f ? -w.x : w.x) + (w.y < 0.0f ? -w.y : w.y) + (w.z < 0.0f ? -w.z : w.z);
    float reach = 0.5f * vx_fmax(hu, hw), pixel = 0.5f * reach, circle = 0.5f * pixel;
    float circle_area = 3.14159265f * circle * circle;
    const float sphere = 0.28867513f; /* sqrt(3) / 6: through the corners of a third of the voxel */
    float sum = 0.0f;
    for (uint p = 0u; p < 16u; ++p) {
        float pu = -reach + (vx_u2f(p & 3u) + 0.5f) * pixel, pw = -reach + (vx_u2f(p >> 2u) + 0.5f) * pixel;
        float best = 0.0f;
        for (uint e = 0u; e < VX_APP_FAITHFUL_ELEMENTS; ++e) {
            uint q = VX_APP_BYTE(vx_load(record, VX_APP_FAITHFUL_OPACITY_WORD + e / 4u), e % 4u);
            if (q == 0u) continue;
            /* the element's centre from the voxel's, (k - 1) / 3 along each axis */
            float ex = vx_u2f(e % 3u) * (1.0f / 3.0f) - (1.0f / 3.0f);
            float ey = vx_u2f((e / 3u) % 3u) * (1.0f / 3.0f) - (1.0f / 3.0f);
            float ez = vx_u2f(e / 9u) * (1.0f / 3.0f) - (1.0f / 3.0f);
            float cu = ex * u.x + ey * u.y + ez * u.z - pu, cw = ex * w.x + ey * w.y + ez * w.z - pw;
            float cover = vx_app_lens_area(vx_sqrt(cu * cu + cw * cw), sphere, circle) / circle_area;
            best = vx_fmax(best, vx_u2f(q) * (1.0f / 255.0f) * cover);
        }
        sum = sum + best;
    }
    return vx_fmin(sum * (1.0f / 16.0f), 1.0f);
}

/* Face f's lighting seen along d: the mean shade of its normals turned to the viewer (the
 * stored ones of a fixed set, else the three extremal normals interpolated at 16 fixed
 * points); a = how many were kept, n their sum. */
VX_APP_FN vx_app_sample vx_app_faithful_face_light(VX_BLOB record, uint f, uint flags, float dx, float dy, float dz,
                                                   vx_app_light light) {
    vx_app_vec n0 = vx_app_byte_vec(vx_load(record, VX_APP_FAITHFUL_FACE_WORD(f, 0u)));
    vx_app_vec n1 = vx_app_byte_vec(vx_load(record, VX_APP_FAITHFUL_FACE_WORD(f, 1u)));
    vx_app_vec n2 = vx_app_byte_vec(vx_load(record, VX_APP_FAITHFUL_FACE_WORD(f, 2u)));
    vx_app_sample got = vx_app_no_sample();
    uint points = VX_APP_FAITHFUL_FIXED(flags, f) != 0u ? VX_APP_FAITHFUL_STORED(flags, f) : 16u;
    for (uint i = 0u; i < points; ++i) {
        vx_app_vec n = i == 0u ? n0 : (i == 1u ? n1 : n2);
        if (points == 16u) { /* sub-triangle i: 10 upward (b1, b2) = (p + 1/3, q + 1/3) / 4, 6 downward + 2/3 */
            uint up = i < 10u ? 1u : 0u, k = i < 10u ? i : i - 10u, row = 0u, limit = up != 0u ? 4u : 3u;
            while (k >= limit - row) k = k - (limit - row), row = row + 1u;
            float offset = up != 0u ? (1.0f / 3.0f) : (2.0f / 3.0f);
            float b1 = (vx_u2f(row) + offset) * 0.25f, b2 = (vx_u2f(k) + offset) * 0.25f, b0 = 1.0f - b1 - b2;
            n.x = b0 * n0.x + b1 * n1.x + b2 * n2.x;
            n.y = b0 * n0.y + b1 * n1.y + b2 * n2.y;
            n.z = b0 * n0.z + b1 * n1.z + b2 * n2.z;
            float length = vx_sqrt(n.x * n.x + n.y * n.y + n.z * n.z);
            if (!(length > 1e-6f)) continue;
            n.x = n.x / length, n.y = n.y / length, n.z = n.z / length;
        }
        if (vx_app_dot(n, dx, dy, dz) >= 0.0f) continue;
        got.r = got.r + vx_app_shade(n, light);
        got.a = got.a + 1.0f;
        got.nx = got.nx + n.x, got.ny = got.ny + n.y, got.nz = got.nz + n.z;
    }
    return got;
}

/* The faithful record along unit ray direction d: the faces that hold data and turn a stored
 * normal to the viewer, each weighted by its projected area, each coloured by its colour
 * times its lighting; the subgrid's opacity. */
VX_APP_FN vx_app_sample vx_app_faithful_sample(VX_BLOB record, float dx, float dy, float dz, vx_app_light light) {
    uint flags = vx_load(record, VX_APP_FAITHFUL_FLAGS_WORD);
    uint w0 = vx_load(record, 0u), w1 = vx_load(record, 1u), w2 = vx_load(record, 2u);
    vx_app_vec e0 = vx_app_byte_vec(w0), e1 = vx_app_byte_vec(w1), e2 = vx_app_byte_vec(w2);
    float s0 = vx_u2f(VX_APP_BYTE(w0, 3u)), s1 = vx_u2f(VX_APP_BYTE(w1, 3u)), s2 = vx_u2f(VX_APP_BYTE(w2, 3u));
    vx_app_sample got = vx_app_no_sample();
    float total = 0.0f;
    for (uint f = 0u; f < 8u; ++f) {
        if (VX_APP_FAITHFUL_HAS_DATA(flags, f) == 0u) continue;
        vx_app_sample lit = vx_app_faithful_face_light(record, f, flags, dx, dy, dz, light);
        if (lit.a <= 0.0f) continue;
        /* the face's corners: on axis k, at -scale where bit k of f is set */
        float k0 = (f & 1u) != 0u ? -s0 : s0, k1 = (f & 2u) != 0u ? -s1 : s1, k2 = (f & 4u) != 0u ? -s2 : s2;
        vx_app_vec a, b; /* edges from corner 0 */
        a.x = k1 * e1.x - k0 * e0.x, a.y = k1 * e1.y - k0 * e0.y, a.z = k1 * e1.z - k0 * e0.z;
        b.x = k2 * e2.x - k0 * e0.x, b.y = k2 * e2.y - k0 * e0.y, b.z = k2 * e2.z - k0 * e0.z;
        float c = (a.y * b.z - a.z * b.y) * dx + (a.z * b.x - a.x * b.z) * dy + (a.x * b.y - a.y * b.x) * dz;
        float area = c < 0.0f ? -c : c;
        uint face0 = vx_load(record, VX_APP_FAITHFUL_FACE_WORD(f, 0u));
        uint face1 = vx_load(record, VX_APP_FAITHFUL_FACE_WORD(f, 1u));
        uint face2 = vx_load(record, VX_APP_FAITHFUL_FACE_WORD(f, 2u));
        float shade = area * lit.r / lit.a, share = area / lit.a;
        got.nx = got.nx + share * lit.nx, got.ny = got.ny + share * lit.ny, got.nz = got.nz + share * lit.nz;
        got.r = got.r + shade * vx_app_linear8(VX_APP_BYTE(face0, 3u));
        got.g = got.g + shade * vx_app_linear8(VX_APP_BYTE(face1, 3u));
        got.b = got.b + shade * vx_app_linear8(VX_APP_BYTE(face2, 3u));
        total = total + area;
    }
    float inv = total > 0.0f ? 1.0f / total : 0.0f;
    got.r = got.r * inv, got.g = got.g * inv, got.b = got.b * inv;
    got.a = vx_app_faithful_opacity(record, dx, dy, dz);
    return vx_app_unit_normal(got);
}
