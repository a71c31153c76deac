#!/usr/bin/env bash
# Installs what is missing, builds, and runs every test with every backend required (a
# missing OpenCL or Vulkan device fails, it does not skip), each test folder where it checks
# the most:
#   Release        the folders no sanitizer runs (headers, embree, tool, install, fuzz, docs)
#                  and the conformance suite, whose Release kernels must agree too (its GPU
#                  groups' four largest agreement tests run only here);
#   TSan           built with clang++-14 and without OpenCL, Vulkan and Embree (which also
#                  proves such a build works with clang); builds and runs just the test
#                  folders brickmap, naadf, svdag, world, entities and sync: the threaded
#                  editing, builds, streaming and entity moves, and the incremental updates;
#   ASan + UBSan   one build with every backend of the other folders (ASAN_FOLDERS) and the
#                  conformance suite, and one ctest over all of them.
#                  UBSan without its vptr and null checks (CMakeLists.txt says why).
# The folders of the ASan pass are not built in Release (VOXRAY_TEST_SKIP): their tests ran
# twice before, and the Release build of their 19 executables took about a third of its
# time. `cmake -B build -DVOXRAY_TEST_SKIP=` builds them there again.
# LeakSanitizer reads scripts/lsan.supp: proven driver leaks only, by library name.
# BUILD_DIR (default build/) names the main build; TSAN_DIR and ASAN_DIR the others
# (default: BUILD_DIR with -tsan, -asan). Each step prints its time.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
ASAN_FOLDERS='cpu|io|mesh|meshing|appearance|malformed|brickmap|naadf|svdag|world|entities|sync|nanovdb|opencl|vulkan'
install_packages
CMAKE_EXTRA="${CMAKE_EXTRA:-} -DVOXRAY_TEST_SKIP=^($ASAN_FOLDERS)\$" configure_and_build
echo "== built in $SECONDS s"

# glibc 2.36 picks memcpy and memset variants on this CPU that use ymm16-31 (EVEX, AVX512VL)
# and return without vzeroupper, leaving the upper vector state dirty. Every later
# legacy-SSE instruction then pays the transition penalty: code compiled without -mavx (the
# tests that do not link voxray::cpu, PoCL's and lavapipe's hosts) runs up to 7x slower (the
# crack test: 38 s, 6 s without). The AVX2 variants end with vzeroupper; this takes them.
# The SIMD lanes and PoCL pick their instruction sets from cpuid, not from glibc, so
# AVX-512 stays tested.
export GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX512F,-AVX512VL

echo "== ctest (all backends required): the Release build's folders"
export VOXRAY_REQUIRE_ALL_BACKENDS=1
(cd "$BUILD_DIR" && ctest --output-on-failure -j"$(nproc)" --timeout 900)

# Sanitizer builds: -O1 with line tables only, which compiles about twice as fast as -O2 -g
# (the ASan pass sets its own level).
# PoCL's cache is the main build's: its kernels are compiled already.
SANITIZED=(-DCMAKE_BUILD_TYPE=RelWithDebInfo "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1 -DNDEBUG" -DVOXRAY_BUILD_TOOLS=OFF
           "-DVOXRAY_POCL_CACHE_DIR=$(cd "$BUILD_DIR" && pwd)/pocl-cache")
export LSAN_OPTIONS="suppressions=$ROOT/scripts/lsan.supp"

tsan_pass() {
    local dir=${TSAN_DIR:-$BUILD_DIR-tsan} start=$SECONDS
    local labels='^(brickmap|naadf|svdag|world|entities|sync)$'
    echo "== ThreadSanitizer (clang++-14, CPU only): tests labelled brickmap, naadf, svdag, world, entities, sync ($dir)"
    cmake -S "$ROOT" -B "$dir" "${SANITIZED[@]}" -DVOXRAY_SANITIZE=thread -DCMAKE_CXX_COMPILER=clang++-14 \
        -DCMAKE_DISABLE_FIND_PACKAGE_OpenCL=ON -DCMAKE_DISABLE_FIND_PACKAGE_Vulkan=ON \
        -DCMAKE_DISABLE_FIND_PACKAGE_embree=ON "-DVOXRAY_TEST_LABELS=$labels" >/dev/null
    cmake --build "$dir" -j"$(nproc)"
    (cd "$dir" && TSAN_OPTIONS="halt_on_error=1 second_deadlock_stack=1" \
        ctest --output-on-failure -j"$(nproc)" --timeout 900 -L "$labels")
    echo "== ThreadSanitizer: passed in $((SECONDS - start)) s"
}

asan_pass() {
    local dir=${ASAN_DIR:-$BUILD_DIR-asan} start=$SECONDS
    echo "== AddressSanitizer + UBSan, every backend ($dir)"
    local ASAN_LABELS="^($ASAN_FOLDERS|conformance)\$"
    # -Og, not -O1: GCC instruments -O1 code slowly (appearance_tests: 55 s plain, 252 s with
    # ASan + UBSan, 118 s at -Og). On a 2-core EPYC, the same hour: the build 1269 -> 812 s,
    # its ctest 381 -> 420 s.
    # No debug info at all (-g0): about 11 % less again, and a report still names every
    # function of its stack (the symbol table); rebuild with -g1 to see its lines.
    cmake -S "$ROOT" -B "$dir" "${SANITIZED[@]}" "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-Og -g0 -DNDEBUG" \
        -DVOXRAY_SANITIZE=address -DVOXRAY_REQUIRE_ALL_BACKENDS=ON \
        "-DVOXRAY_TEST_LABELS=$ASAN_LABELS" >/dev/null
    cmake --build "$dir" -j"$(nproc)"
    # Lavapipe (mesa 22.3.6-1+deb12u2) loses 128 bytes per VkInstance, and the Vulkan loader unloads
    # it at vkDestroyInstance, so LeakSanitizer reports them from "<unknown module>", which
    # no suppression by library name can match. Keeping the driver loaded for the whole
    # process (preloaded, after ASan's runtime, which must come first) keeps what it holds
    # reachable from its own globals; leaks of our code are still reported. CPU-only tests
    # load it too, unused.
    local lvp preload=""
    lvp=$(sed -n 's/.*"library_path": *"\([^"]*\)".*/\1/p' /usr/share/vulkan/icd.d/lvp_icd*.json 2>/dev/null | head -n1)
    if [ -n "$lvp" ] && [ -f "$lvp" ]; then preload="$(g++ -print-file-name=libasan.so) $lvp"; fi
    # One ctest over the CPU and GPU labels, so that the long conformance tests of all three
    # backends overlap (tests/conformance gives them a COST: they start first).
    # until-pass:2: under load, LeakSanitizer's stop-the-world tracer itself can crash at
    # exit while PoCL's worker threads wind down ("Tracer caught signal 11", 1 run in ~10
    # here, never alone); a real leak or error fails both runs.
    echo "== AddressSanitizer + UBSan: folders $ASAN_FOLDERS, conformance"
    (cd "$dir" && LD_PRELOAD="$preload" ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 \
        ctest --output-on-failure -j"$(nproc)" --timeout 900 --repeat until-pass:2 -L "$ASAN_LABELS")
    echo "== AddressSanitizer + UBSan: passed in $((SECONDS - start)) s"
}

tsan_pass
asan_pass
echo "== all tests passed in $SECONDS s"
