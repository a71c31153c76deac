#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole ctest suite with every backend
# required (a missing OpenCL or Vulkan device fails, it does not skip); then builds the
# CPU parts again under AddressSanitizer + UBSan and runs them.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
install_packages
configure_and_build

echo "== ctest (all backends required)"
export VOXRAY_REQUIRE_ALL_BACKENDS=1
(cd "$BUILD_DIR" && ctest --output-on-failure -j"$(nproc)" --timeout 900)

echo "== AddressSanitizer + UBSan build (CPU parts)"
ASAN_DIR="$BUILD_DIR-asan"
cmake -S "$ROOT" -B "$ASAN_DIR" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DVOXRAY_SANITIZE=ON -DVOXRAY_BUILD_TOOLS=OFF >/dev/null
ASAN_TESTS=(test_cpu_dense_edge_cases test_cpu_dense_oracle test_cpu_simd_vs_scalar test_vox_reader test_mesh
           test_brickmap_host)
cmake --build "$ASAN_DIR" -j"$(nproc)" --target "${ASAN_TESTS[@]}"
(cd "$ASAN_DIR" && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    ctest --output-on-failure -j"$(nproc)" -R "^($(IFS='|'; echo "${ASAN_TESTS[*]}"))\$")
echo "== all tests passed"
