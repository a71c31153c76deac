#!/usr/bin/env bash
# Installs what is missing, builds, and runs the whole ctest suite with every backend
# required (a missing OpenCL or Vulkan device fails, it does not skip). Then two CPU-only
# passes, each a build without OpenCL, Vulkan and Embree (which also proves such a build
# works) that configures only the test folders its ctest labels select:
#   ASan + UBSan  builds and runs every CPU label (cpu, io, mesh, malformed, brickmap, naadf, svdag, world, sync, conformance, nanovdb);
#   TSan          built with clang++-14 (so clang compiles every CPU test too, but malformed, whose operator new
#                 clashes with clang's static TSan runtime), runs brickmap, naadf, svdag, world and sync:
#                 the threaded editing, builds and streaming, and the incremental updates;
# and one more ASan + UBSan pass with OpenCL and Vulkan: every test labelled opencl or
# vulkan (the backend tests, both GPU conformance groups, sync, brickmap tracing).
# LeakSanitizer reads scripts/lsan.supp: proven driver leaks only, by library name.
# BUILD_DIR (default build/) names the main build; ASAN_DIR, TSAN_DIR and ASAN_GPU_DIR
# the others (default: BUILD_DIR with -asan, -tsan, -asan-gpu).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
install_packages
configure_and_build

echo "== ctest (all backends required)"
export VOXRAY_REQUIRE_ALL_BACKENDS=1
(cd "$BUILD_DIR" && ctest --output-on-failure -j"$(nproc)" --timeout 900)

CPU_LABELS='^(cpu|io|mesh|malformed|brickmap|naadf|svdag|world|sync|conformance|nanovdb)$'
CPU_ONLY=(-DCMAKE_DISABLE_FIND_PACKAGE_OpenCL=ON -DCMAKE_DISABLE_FIND_PACKAGE_Vulkan=ON
          -DCMAKE_DISABLE_FIND_PACKAGE_embree=ON -DVOXRAY_BUILD_TOOLS=OFF)
# Sanitizer builds: -O1 with line tables only, which compiles about twice as fast as -O2 -g.
SANITIZED=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG")

# cpu_pass NAME DIR BUILD_LABELS RUN_LABELS [CMAKE_ARGS...]: a CPU-only build of the test
# folders whose label matches BUILD_LABELS (VOXRAY_TEST_LABELS), then ctest -L RUN_LABELS there.
cpu_pass() {
    local name=$1 dir=$2 build_labels=$3 labels=$4 start=$SECONDS
    shift 4
    echo "== $name: CPU-only build of tests labelled $build_labels, running $labels ($dir)"
    cmake -S "$ROOT" -B "$dir" "${CPU_ONLY[@]}" "-DVOXRAY_TEST_LABELS=$build_labels" "$@" >/dev/null
    cmake --build "$dir" -j"$(nproc)"
    (cd "$dir" && ctest --output-on-failure -j"$(nproc)" --timeout 900 -L "$labels")
    echo "== $name: passed in $((SECONDS - start)) s"
}

export LSAN_OPTIONS="suppressions=$ROOT/scripts/lsan.supp"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
    cpu_pass "AddressSanitizer + UBSan" "${ASAN_DIR:-$BUILD_DIR-asan}" "$CPU_LABELS" "$CPU_LABELS" "${SANITIZED[@]}" \
    -DVOXRAY_SANITIZE=address
# One clang build serves both: a separate clang++-14 build of every CPU test cost as much
# as this one, and CI time is what bounds how much the suite can run.
TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" \
    cpu_pass "ThreadSanitizer (clang++-14)" "${TSAN_DIR:-$BUILD_DIR-tsan}" "${CPU_LABELS/malformed|/}" \
    '^(brickmap|naadf|svdag|world|sync)$' \
    "${SANITIZED[@]}" -DVOXRAY_SANITIZE=thread -DCMAKE_CXX_COMPILER=clang++-14
# ASan + UBSan with OpenCL and Vulkan: configure the folders that hold such tests, build
# only the tests labelled opencl or vulkan (ctest -N lists them before anything is built;
# test and target names are the same), run them. The build's own PoCL cache starts cold,
# so PoCL compiles every kernel here: the path of its known leak (scripts/lsan.supp).
gpu_asan_pass() {
    local dir=${ASAN_GPU_DIR:-$BUILD_DIR-asan-gpu} labels='^(opencl|vulkan)$' start=$SECONDS
    echo "== AddressSanitizer + UBSan with OpenCL and Vulkan: tests labelled $labels ($dir)"
    cmake -S "$ROOT" -B "$dir" -DVOXRAY_REQUIRE_ALL_BACKENDS=ON -DVOXRAY_BUILD_TOOLS=OFF \
        '-DVOXRAY_TEST_LABELS=^(opencl|vulkan|conformance|sync|brickmap|svdag|world)$' "${SANITIZED[@]}" \
        -DVOXRAY_SANITIZE=address >/dev/null
    local targets
    targets=$(cd "$dir" && ctest -N -L "$labels" | sed -n 's/^ *Test *#[0-9]*: //p')
    [ -n "$targets" ] || { echo "no tests labelled $labels"; return 1; }
    # shellcheck disable=SC2086
    cmake --build "$dir" -j"$(nproc)" --target $targets
    # Lavapipe (mesa 22.3.6-1+deb12u2) loses 128 bytes per VkInstance, and the Vulkan loader unloads
    # it at vkDestroyInstance, so LeakSanitizer reports them from "<unknown module>", which
    # no suppression by library name can match. Keeping the driver loaded for the whole
    # process (preloaded, after ASan's runtime, which must come first) keeps what it holds
    # reachable from its own globals; leaks of our code are still reported.
    local lvp preload=""
    lvp=$(sed -n 's/.*"library_path": *"\([^"]*\)".*/\1/p' /usr/share/vulkan/icd.d/lvp_icd*.json 2>/dev/null | head -n1)
    if [ -n "$lvp" ] && [ -f "$lvp" ]; then preload="$(g++ -print-file-name=libasan.so) $lvp"; fi
    # until-pass:2: under load, LeakSanitizer's stop-the-world tracer itself can crash at
    # exit while PoCL's worker threads wind down ("Tracer caught signal 11", 1 run in ~10
    # here, never alone); a real leak or error fails both runs.
    (cd "$dir" && LD_PRELOAD="$preload" ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
        ctest --output-on-failure -j"$(nproc)" --timeout 900 --repeat until-pass:2 -L "$labels")
    echo "== AddressSanitizer + UBSan with OpenCL and Vulkan: passed in $((SECONDS - start)) s"
}
gpu_asan_pass
echo "== all tests passed"
