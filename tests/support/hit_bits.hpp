// Comparing hit records bit for bit, and printing rays and hits in failure messages.
#pragma once
#include <cstdio>
#include <cstring>
#include <string>

#include "voxray/core/hit.hpp"
#include "voxray/core/ray.hpp"

namespace voxray::test {

inline bool identical(const hit& a, const hit& b) { return std::memcmp(&a, &b, sizeof(hit)) == 0; }

// Bytes equal, except that t = -0 and t = +0 count as equal: lavapipe (and PoCL) may
// compute the kernel's `0.0f - o` as -0 for o = +0, and Vulkan does not require signed
// zeros to be preserved, so rays starting exactly on a boundary report t = -0 where the
// CPU says +0. Nothing else is forgiven.
inline bool same_bits(const hit& a, const hit& b) {
    if (std::memcmp(&a, &b, sizeof(hit)) == 0) return true;
    if (a.t != 0.0f || b.t != 0.0f) return false;
    hit x = a, y = b;
    x.t = y.t = 0.0f;
    return std::memcmp(&x, &y, sizeof(hit)) == 0;
}

// Whether a and b differ only in the sign of a zero t (counted by the backend tests).
inline bool differ_in_zero_sign(const hit& a, const hit& b) {
    return std::memcmp(&a, &b, sizeof(hit)) != 0 && same_bits(a, b);
}

inline std::string describe(const ray& r) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "o=(%.9g %.9g %.9g) d=(%.9g %.9g %.9g) t=[%.9g, %.9g]", r.origin.x, r.origin.y,
                  r.origin.z, r.direction.x, r.direction.y, r.direction.z, r.tmin, r.tmax);
    return buf;
}

inline std::string describe(const hit& h) {
    char buf[200];
    std::snprintf(buf, sizeof buf, "%s t=%.9g voxel=(%d %d %d) face=%s material=%u steps=%u status=%u",
                  h.is_hit() ? "hit" : "miss", h.t, h.voxel.x, h.voxel.y, h.voxel.z, face_name(h.normal), h.material,
                  h.steps, h.status);
    return buf;
}

}  // namespace voxray::test
