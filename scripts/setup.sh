#!/usr/bin/env bash
# Installs the Debian 12 packages voxray needs (only those missing) and configures and
# builds it. Sourced by demo.sh and test.sh; BUILD_DIR and CMAKE_EXTRA may be set.
set -euo pipefail

PACKAGES=(cmake make g++ libglm-dev libembree-dev libtbb-dev opencl-headers opencl-clhpp-headers
          ocl-icd-opencl-dev pocl-opencl-icd clinfo libvulkan-dev mesa-vulkan-drivers vulkan-tools
          glslang-tools spirv-tools libgtest-dev libbenchmark-dev clang-14 libclang-rt-14-dev
          libnanovdb-dev libcli11-dev nlohmann-json3-dev libstb-dev python3-matplotlib libtinygltf-dev
          libmeshoptimizer-dev libopenmpi-dev openmpi-bin openssh-client)
# openssh-client: Open MPI's mpirun wants an rsh agent even when every rank is local.

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
BUILD_DIR="${BUILD_DIR:-$ROOT/build}"

install_packages() {
    local missing=()
    for p in "${PACKAGES[@]}"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
    done
    if [ ${#missing[@]} -eq 0 ]; then
        echo "== packages: all ${#PACKAGES[@]} present"
        return
    fi
    echo "== packages: installing ${missing[*]}"
    local sudo=""
    [ "$(id -u)" -ne 0 ] && sudo="sudo"
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

# configure_and_build [TARGET...]: everything, or only the targets named (and what they need).
configure_and_build() {
    echo "== configure ($BUILD_DIR)"
    cmake -S "$ROOT" -B "$BUILD_DIR" -DCMAKE_BUILD_TYPE=Release -DVOXRAY_REQUIRE_ALL_BACKENDS=ON ${CMAKE_EXTRA:-} >/dev/null
    echo "== build ($(nproc) jobs${1:+: $*})"
    cmake --build "$BUILD_DIR" -j"$(nproc)" ${1:+--target "$@"}
}

# PoCL needs a writable cache directory, or it reports zero devices.
export POCL_CACHE_DIR="${POCL_CACHE_DIR:-$BUILD_DIR/pocl-cache}"
mkdir -p "$POCL_CACHE_DIR" 2>/dev/null || true

# Checks that every scene of $SCENES (space-separated: files or builtin:NAME) exists and puts
# them into the array `scenes`, files relative to $ROOT: run from $ROOT, a results file's
# recorded command then names no directory of this machine (tests/docs checks).
relative_scenes() {
    scenes=()
    for s in $SCENES; do
        [[ "$s" == builtin:* || -f "$s" ]] || { echo "scene $s not found (set VOXRAY_DATA_DIR)"; return 1; }
        if [[ "$s" == builtin:* ]]; then scenes+=("$s"); else scenes+=("$(realpath -m --relative-to="$ROOT" "$s")"); fi
    done
}
