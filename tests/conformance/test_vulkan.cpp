// The conformance suite on Vulkan (lavapipe on CI: a missing device fails, it never skips).
#include "conformance.hpp"
#include "voxray/vulkan.hpp"

namespace voxray::test {

// lavapipe compiles SPIR-V with LLVM like the C++ and honours IEEE division, so its hits
// are the CPU's bit for bit; a GPU may round 1/d differently, which may show as ties only.
template <>
struct float_rules<vulkan> {
    static constexpr bool signed_zero_t = true;  // see hit_bits.hpp
    template <class Engine>
    static bool exact(Engine& e) { return e.device_properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU; }
};

VOXRAY_CONFORMANCE(vulkan, vulkan);

}  // namespace voxray::test
