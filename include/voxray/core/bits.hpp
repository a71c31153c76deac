// Small bit helpers shared by the host-side builders.
#pragma once
#include <bit>
#include <cstdint>

namespace voxray::bits {

constexpr std::uint32_t ceil_div(std::uint32_t a, std::uint32_t b) { return (a + b - 1) / b; }
constexpr std::uint64_t ceil_div64(std::uint64_t a, std::uint64_t b) { return (a + b - 1) / b; }
constexpr bool test(const std::uint32_t* words, std::uint32_t bit) { return (words[bit >> 5] >> (bit & 31)) & 1u; }
constexpr void set(std::uint32_t* words, std::uint32_t bit) { words[bit >> 5] |= 1u << (bit & 31); }
constexpr void clear(std::uint32_t* words, std::uint32_t bit) { words[bit >> 5] &= ~(1u << (bit & 31)); }
inline int popcount(std::uint32_t w) { return std::popcount(w); }

}  // namespace voxray::bits
