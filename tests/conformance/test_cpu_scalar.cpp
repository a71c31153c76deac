// The conformance suite on the scalar-lane CPU backend (test_conformance_cpu, with cpu):
// its own file so that the two instantiations compile in parallel.
#include "conformance.hpp"

namespace voxray::test {
VOXRAY_CONFORMANCE(cpu_scalar, cpu_scalar);
}
