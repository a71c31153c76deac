// The conformance suite on OpenCL (PoCL on CI: a missing device fails, it never skips).
#include "conformance.hpp"
#include "voxray/opencl.hpp"

namespace voxray::test {

// PoCL divides with correct rounding; a device that does not must still agree, tie-free.
template <>
struct float_rules<opencl> {
    static constexpr bool signed_zero_t = true;  // see hit_bits.hpp
    template <class Engine>
    static bool exact(Engine& e) { return e.correctly_rounded_division(); }
};

VOXRAY_CONFORMANCE(opencl, opencl);

}  // namespace voxray::test
