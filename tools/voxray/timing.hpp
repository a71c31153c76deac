// Timing helpers of the tool's benchmarks: seconds since a start, and percentiles of samples.
#pragma once
#include <algorithm>
#include <chrono>
#include <vector>

namespace voxray::tool {

inline double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The p-th percentile (0..1, nearest rank) of the samples; 0 for none.
inline double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0;
    std::sort(v.begin(), v.end());
    return v[std::min(v.size() - 1, std::size_t(p * double(v.size() - 1) + 0.5))];
}

}  // namespace voxray::tool
