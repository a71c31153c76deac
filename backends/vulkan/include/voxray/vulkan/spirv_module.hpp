// The SPIR-V module that traces one structure kernel (the trace mode is a specialization
// constant: one pipeline per mode from the one module), its frame passes' module where it
// has one, and its compositing walk's. The generated table
// (voxray/generated/vulkan_modules.hpp) lists one row per voxray_add_structure call;
// find_modules is evaluated at compile time, so a structure without modules is a
// compile-time error, not a run-time surprise.
#pragma once
#include <cstdint>
#include <span>
#include <string_view>

namespace voxray::vulkan_detail {

struct spirv_modules {
    std::string_view name;
    std::span<const std::uint32_t> trace;
    std::span<const std::uint32_t> passes = {};  // structures registered with PASSES (the world's frame)
    std::span<const std::uint32_t> appearance = {};  // the compositing walk (appearance/walk.inc)
};

}  // namespace voxray::vulkan_detail
