// The checksum of voxray's files (brickmap .vxbm, NAADF .vxna): FNV-1a, 64 bits. Not a
// cryptographic hash: it catches truncation and corruption, not tampering.
#pragma once
#include <cstddef>
#include <cstdint>

namespace voxray {

struct fnv64 {
    std::uint64_t h = 0xcbf29ce484222325ull;
    void bytes(const void* p, std::size_t n) {
        auto* c = static_cast<const unsigned char*>(p);
        for (std::size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 0x100000001b3ull;
    }
    // Word-at-a-time variant for the blob (4x fewer multiplies; every word still
    // changes the state bijectively, so any single corrupted word changes the sum).
    void words(const std::uint32_t* w, std::size_t n) {
        for (std::size_t i = 0; i < n; ++i) h = (h ^ w[i]) * 0x100000001b3ull;
    }
};

}  // namespace voxray
