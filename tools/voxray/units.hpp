// Figures for people: a duration, a rate or a byte count with the unit that keeps three
// significant digits ("4.12 us", "1.35 M/s", "12.0 KiB"), so that a 4 µs edit does not
// print as "0.00 ms" nor a rate as a 10-digit integer.
#pragma once
#include <cmath>
#include <cstdio>
#include <string>

namespace voxray::tool {

namespace units_detail {
inline std::string three_digits(double v, const char* unit) {
    char text[48];
    double a = std::fabs(v);
    std::snprintf(text, sizeof text, a >= 100 || a == 0 ? "%.0f %s" : a >= 10 ? "%.1f %s" : "%.2f %s", v, unit);
    return text;
}
}  // namespace units_detail

inline std::string human_seconds(double s) {
    using units_detail::three_digits;
    double a = std::fabs(s);
    if (a == 0 || a >= 1) return three_digits(s, "s");
    if (a >= 1e-3) return three_digits(s * 1e3, "ms");
    if (a >= 1e-6) return three_digits(s * 1e6, "us");
    return three_digits(s * 1e9, "ns");
}

// `per_second` things a second: "135 voxel writes/s", "1.35 M voxel writes/s".
inline std::string human_rate(double per_second, const std::string& what) {
    const char* prefix[] = {"", "k ", "M ", "G ", "T "};
    int p = 0;
    while (std::fabs(per_second) >= 1000 && p < 4) per_second /= 1000, ++p;
    return units_detail::three_digits(per_second, (prefix[p] + what + "/s").c_str());
}

inline std::string human_bytes(double bytes) {
    const char* unit[] = {"B", "KiB", "MiB", "GiB", "TiB"};
    int u = 0;
    while (std::fabs(bytes) >= 1024 && u < 4) bytes /= 1024, ++u;
    return units_detail::three_digits(bytes, unit[u]);
}

}  // namespace voxray::tool
