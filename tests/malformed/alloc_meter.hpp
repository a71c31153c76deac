// Counts the bytes live through operator new (replaced in alloc_meter.cpp), so a test
// can bound the memory a loader takes for a small input without limiting the process
// (an address-space limit would break the sanitizers' shadow memory).
#pragma once
#include <cstddef>

namespace voxray::test::malformed {

std::size_t live_bytes();
std::size_t peak_bytes();
void reset_peak();  // peak := live

}  // namespace voxray::test::malformed
