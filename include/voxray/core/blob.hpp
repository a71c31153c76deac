// The pointer-free bytes every structure hands to the backends: 32-bit words, every
// link an offset in words. The same words go to the CPU, OpenCL and Vulkan.
#pragma once
#include <cstdint>
#include <span>
#include <vector>

#include "voxray/core/error.hpp"

namespace voxray {

using blob_words = std::vector<std::uint32_t>;

// Per-lane gathers address words with signed 32-bit indices (AVX2/AVX-512), and the GPU
// kernels use 32-bit word offsets: 2^31 words = 8 GiB is the largest blob.
inline constexpr std::uint64_t max_blob_words = std::uint64_t(1) << 31;

inline void check_blob_size(const char* structure, std::uint64_t words) {
    if (words >= max_blob_words)
        fail(structure, " would need ", words * 4, " bytes, above the blob limit of ", max_blob_words * 4,
             " bytes (32-bit word offsets)");
}

}  // namespace voxray
