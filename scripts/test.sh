#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole ctest suite with every backend
# required (a missing OpenCL or Vulkan device fails, it does not skip). Then three CPU-only
# passes, each a build without OpenCL, Vulkan and Embree (which also proves such a build
# works) that configures and runs only the test folders its ctest labels select:
#   ASan + UBSan  every CPU label (cpu, io, mesh, brickmap, sync, conformance, nanovdb);
#   TSan          brickmap and sync: the threaded editing and the incremental updates;
#   clang++-14    every CPU label, built with clang instead of g++.
# BUILD_DIR (default build/) names the main build; ASAN_DIR, TSAN_DIR and CLANG_DIR the
# others (default: BUILD_DIR with -asan, -tsan, -clang).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
install_packages
configure_and_build

echo "== ctest (all backends required)"
export VOXRAY_REQUIRE_ALL_BACKENDS=1
(cd "$BUILD_DIR" && ctest --output-on-failure -j"$(nproc)" --timeout 900)

CPU_LABELS='^(cpu|io|mesh|malformed|brickmap|naadf|sync|conformance|nanovdb)$'
CPU_ONLY=(-DCMAKE_DISABLE_FIND_PACKAGE_OpenCL=ON -DCMAKE_DISABLE_FIND_PACKAGE_Vulkan=ON
          -DCMAKE_DISABLE_FIND_PACKAGE_embree=ON -DVOXRAY_BUILD_TOOLS=OFF)
# Sanitizer builds: -O1 with line tables only, which compiles about twice as fast as -O2 -g.
SANITIZED=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG")

# cpu_pass NAME DIR LABELS [CMAKE_ARGS...]: a CPU-only build of the test folders whose
# label matches LABELS (VOXRAY_TEST_LABELS), then ctest -L LABELS there.
cpu_pass() {
    local name=$1 dir=$2 labels=$3 start=$SECONDS
    shift 3
    echo "== $name: CPU-only build, tests labelled $labels ($dir)"
    cmake -S "$ROOT" -B "$dir" "${CPU_ONLY[@]}" "-DVOXRAY_TEST_LABELS=$labels" "$@" >/dev/null
    cmake --build "$dir" -j"$(nproc)"
    (cd "$dir" && ctest --output-on-failure -j"$(nproc)" --timeout 900 -L "$labels")
    echo "== $name: passed in $((SECONDS - start)) s"
}

ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    cpu_pass "AddressSanitizer + UBSan" "${ASAN_DIR:-$BUILD_DIR-asan}" "$CPU_LABELS" "${SANITIZED[@]}" \
    -DVOXRAY_SANITIZE=address
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" \
    cpu_pass "ThreadSanitizer" "${TSAN_DIR:-$BUILD_DIR-tsan}" '^(brickmap|sync)$' "${SANITIZED[@]}" \
    -DVOXRAY_SANITIZE=thread
cpu_pass "clang++-14" "${CLANG_DIR:-$BUILD_DIR-clang}" "$CPU_LABELS" -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CXX_COMPILER=clang++-14
echo "== all tests passed"
