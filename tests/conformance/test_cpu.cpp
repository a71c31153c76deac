// The conformance suite on the SIMD-lane CPU backend (test_conformance_cpu, with cpu_scalar).
#include "conformance.hpp"

namespace voxray::test {
VOXRAY_CONFORMANCE(cpu, cpu);
}
