#!/usr/bin/env bash
# The GPU run: the benchmark matrix on the GPU backends (OpenCL, Vulkan) at 3840 x 2160 on
# the shared scenes of the README's NAADF table (meshes voxelized at 2048), then the world's
# GPU-driven passes on a tiled terrain world, then a table (scripts/device_table.py).
# Sized to end inside 8 minutes on a lent GPU machine, the build included.
#
#   scripts/device_bench.sh [--small] [RESULTS_DIR]      (default docs/bench/device)
#
# --small: a smoke run for this machine (lavapipe and PoCL), 320 x 180, one scene at 128;
#          tests/tool/device_bench.sh runs it so that the script keeps working.
# PARTS: which parts run (default "matrix world groups"; a rerun may take fewer).
# VOXRAY_TOOL=path: use this built tool instead of configuring and building one (a
#          machine without the build's packages: scripts/device_pack.sh bundles a tool).
# Then, while the run is inside its time (GROUP_SWEEP_UNTIL seconds), the same rows of one
# scene at other work-group sizes (VOXRAY_GROUP_SIZE), to tune the default from.
# Writes RESULTS_DIR/device_results.jsonl (bench rows: Mrays/s of the whole trace and of the
# kernels alone, from GPU timestamps), device_world_passes.jsonl, device_groups.jsonl and
# device_table.md.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
SMALL=0
if [[ "${1:-}" == --small ]]; then SMALL=1; shift; fi
RESULTS="$(realpath -m "${1:-$ROOT/docs/bench/device}")"
DATA="${VOXRAY_DATA_DIR:-$ROOT/../shared/data}"
WORK="${WORK:-/tmp/voxray-device-bench}"
if [[ $SMALL == 1 ]]; then
    WIDTH=320 HEIGHT=180 RESOLUTION=128 RUNS=1 FRAMES=2 TILE="2 2 1" GROUP_SIZES="32"
    SCENES="$DATA/vox/mmmm_scene_church1.vox" SWEEP_SCENE="$DATA/vox/mmmm_scene_church1.vox"
else
    WIDTH=3840 HEIGHT=2160 RESOLUTION=2048 RUNS=3 FRAMES=8 TILE="4 4 1" GROUP_SIZES="32 128 256"
    source "$ROOT/scripts/device_scenes.sh"
    SCENES="${DEVICE_SCENES[*]/#/$DATA/}" SWEEP_SCENE="$DATA/mesh/dabrovic_sponza.obj"
fi
STRUCTURES="${STRUCTURES:-naadf,brickmap,svdag,world,dense}"
relative_scenes
cd "$ROOT"
# Paths relative to the repository: the results record them (tests/docs: no machine paths).
relative() { realpath -m --relative-to="$ROOT" "$1"; }
RESULTS="$(relative "$RESULTS")" WORK="$(relative "$WORK")"

if [[ -n "${VOXRAY_TOOL:-}" ]]; then
    TOOL="$(relative "$VOXRAY_TOOL")"
else
    install_packages
    configure_and_build voxray_tool
    TOOL="$(relative "$BUILD_DIR/voxray")"
fi
# The GPU backends this tool has (a build may lack one: then the table shows it missing).
BACKENDS="$("$TOOL" bench --help | grep -o 'cpu,cpu-scalar[a-z,-]*' | head -n1 | tr ',' '\n' |
    grep -vx 'cpu\|cpu-scalar' | paste -sd, -)"
[[ -n "$BACKENDS" ]] || { echo "device_bench: this tool has no GPU backend (OpenCL or Vulkan)"; exit 1; }
mkdir -p "$RESULTS" "$WORK"

matrix() {
    echo "== $(date -u +%FT%TZ) matrix: $WIDTH x $HEIGHT, $RUNS runs, $STRUCTURES on $BACKENDS"
    # bench exits 1 when a row disagrees or fails; the table shows which, so go on.
    "$TOOL" bench "${scenes[@]}" --resolution "$RESOLUTION" --width "$WIDTH" --height "$HEIGHT" --runs "$RUNS" \
        --structures "$STRUCTURES" --backends "$BACKENDS" --out "$RESULTS/device_results.jsonl" ||
        echo "== some rows disagree or failed: see the table"
}

world() {
    echo "== $(date -u +%FT%TZ) world: builtin:terrain tiled $TILE, 128^3 chunks"
    rm -rf "$WORK/world" "$RESULTS/device_world_passes.jsonl"
    # shellcheck disable=SC2086
    "$TOOL" world-build builtin:terrain --tile $TILE --chunk-bits 7 --colours --out "$WORK/world" | tail -n1
    for backend in ${BACKENDS//,/ }; do
        for mode in --passes ""; do  # the GPU-driven passes, then the same path traced ray by ray
            echo "== $(date -u +%FT%TZ) world-fly ${mode:-(ray by ray)} on $backend"
            # shellcheck disable=SC2086
            "$TOOL" world-fly "$WORK/world" $mode --backend "$backend" --frames "$FRAMES" --width "$WIDTH" \
                --height "$HEIGHT" --json "$RESULTS/device_world_passes.jsonl" | tail -n2 ||
                echo "== world-fly ${mode:-(ray by ray)} on $backend failed"
        done
    done
}

groups() {
    rm -f "$RESULTS/device_groups.jsonl"
    for size in $GROUP_SIZES; do
        if ((SECONDS > ${GROUP_SWEEP_UNTIL:-420})); then echo "== no time left for work-group size $size"; break; fi
        echo "== $(date -u +%FT%TZ) work-group size $size"
        VOXRAY_GROUP_SIZE=$size "$TOOL" bench "$(relative "$SWEEP_SCENE")" --resolution "$RESOLUTION" \
            --width "$WIDTH" --height "$HEIGHT" --runs "$RUNS" --structures naadf,world --rays primary,shadow \
            --backends "$BACKENDS" --out "$WORK/groups_$size.jsonl" | tail -n1 || echo "== some rows disagree or failed"
        cat "$WORK/groups_$size.jsonl" >> "$RESULTS/device_groups.jsonl"
    done
}

for part in ${PARTS:-matrix world groups}; do
    case "$part" in
        matrix | world | groups) "$part" ;;
        *) echo "device_bench: PARTS holds '$part'; the parts are matrix, world and groups"; exit 2 ;;
    esac
done
echo "== $(date -u +%FT%TZ) table"
python3 scripts/device_table.py "$RESULTS/device_results.jsonl" \
    --passes "$RESULTS/device_world_passes.jsonl" --groups "$RESULTS/device_groups.jsonl" --out "$RESULTS/device_table.md"
