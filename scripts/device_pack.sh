#!/usr/bin/env bash
# The GPU run on a machine that has a GPU driver but none of the build's packages (no
# glslang, Embree, Vulkan or OpenCL loader, no package registry): the tool built here,
# bundled with the shared libraries it links, the scenes of the run and the GL/Vulkan
# loader packages the NVIDIA driver's Vulkan ICD needs.
#
#   scripts/device_pack.sh pack DIR            here: build the tool, write DIR/bundle.tar.gz
#                                              and DIR/gl/*.deb (DIR: a git-ignored folder)
#   scripts/device_pack.sh run DIR RESULTS [--small]
#                                              there: unpack, point the loaders at the
#                                              driver, run scripts/device_bench.sh (into
#                                              DIR/results), copy its files to RESULTS
# x86-64 both ends; the tool is built for x86-64-v3 (not -march=native), so it runs on any
# AVX2 host. glibc is the host's (the bundle leaves it out: the GPU image's is newer).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
verb="${1:?pack DIR or run DIR RESULTS}"
DIR="$(realpath -m "${2:?a folder}")"
DATA="${VOXRAY_DATA_DIR:-$ROOT/../shared/data}"
source "$ROOT/scripts/device_scenes.sh"  # DEVICE_SCENES: the scenes device_bench.sh traces
# Debian packages whose libraries the NVIDIA Vulkan ICD (libGLX_nvidia) loads.
GL_PACKAGES=(libglvnd0 libglx0 libegl1 libopengl0 libgl1 libgles2)

pack() {
    source "$ROOT/scripts/setup.sh"
    install_packages
    configure_and_build voxray_tool
    local stage
    stage="$(mktemp -d)"
    mkdir -p "$stage/bundle/lib" "$stage/bundle/data"
    cp "$BUILD_DIR/voxray" "$stage/bundle/voxray.bin"
    # Every linked library but glibc's own (libc, libm, the dynamic loader...).
    ldd "$BUILD_DIR/voxray" | awk '$3 ~ /^\// {print $3}' |
        grep -Ev '/(libc|libm|libdl|librt|libpthread|ld-linux[^/]*)\.so' |
        xargs -I{} cp -L {} "$stage/bundle/lib/"
    # The tool as a command: its libraries first, the caller's environment otherwise untouched.
    cat > "$stage/bundle/voxray" <<'EOF'
#!/bin/sh
here="$(dirname "$0")"  # as called: the results record the tool's path, relative where it was
LD_LIBRARY_PATH="$here/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}" exec "$here/voxray.bin" "$@"
EOF
    chmod +x "$stage/bundle/voxray"
    for s in "${DEVICE_SCENES[@]}"; do
        mkdir -p "$stage/bundle/data/$(dirname "$s")"
        cp "$DATA/$s" "$stage/bundle/data/$s"
    done
    mkdir -p "$DIR/gl"
    tar -C "$stage" -czf "$DIR/bundle.tar.gz" bundle
    rm -rf "$stage"
    (cd "$DIR/gl" && apt-get download "${GL_PACKAGES[@]}" >/dev/null)
    du -sh "$DIR/bundle.tar.gz" "$DIR/gl"
}

run() {
    local results="${3:?a results folder}"
    for deb in "$DIR"/gl/*.deb; do [[ -e "$deb" ]] && dpkg -x "$deb" /; done
    ldconfig
    tar -C "$DIR" -xzf "$DIR/bundle.tar.gz"  # inside the repository: the results name relative paths
    local drv=/usr/local/nvidia
    # Vulkan: the driver's ICD manifest, where the loader would not look by itself.
    local icd
    icd="$(find "$drv" /usr/share/vulkan /etc/vulkan -name 'nvidia_icd*.json' 2>/dev/null | head -n1 || true)"
    if [[ -n "$icd" ]]; then export VK_DRIVER_FILES="$icd"; echo "== Vulkan ICD: $icd"; fi
    # OpenCL: an ICD entry for the driver's OpenCL library, where it has one.
    local ocl
    ocl="$(find "$drv" /usr/lib /usr/lib64 -name 'libnvidia-opencl.so*' 2>/dev/null | head -n1 || true)"
    if [[ -n "$ocl" ]]; then
        mkdir -p /etc/OpenCL/vendors
        echo "$ocl" > /etc/OpenCL/vendors/nvidia.icd
        echo "== OpenCL ICD: $ocl"
    else
        echo "== no libnvidia-opencl found: OpenCL rows will name the missing device"
    fi
    nvidia-smi -L || true
    VOXRAY_TOOL="$DIR/bundle/voxray" VOXRAY_DATA_DIR="$DIR/bundle/data" WORK="$DIR/work" \
        "$ROOT/scripts/device_bench.sh" "${@:4}" "$DIR/results"
    mkdir -p "$results"
    cp "$DIR"/results/device_* "$results/"
}

case "$verb" in
    pack) pack ;;
    run) run "$@" ;;
    *) echo "device_pack.sh: pack DIR or run DIR RESULTS, not '$verb'"; exit 2 ;;
esac
