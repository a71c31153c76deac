#!/usr/bin/env bash
# Issue 27's measurements: world builds on 1, 2 and 4 MPI ranks (one build thread each;
# oversubscribed past the cores there are) with the dynamic and the static schedule, beside
# one process on one and on every thread, on a uniform world (a tiled terrain) and a skewed
# one (a real mesh: its triangles crowd a few chunks); then, with --chunk-times, every chunk
# job's time in a real build at a large resolution, from which scripts/world_scaling_table.py
# simulates the makespan on 8 to 512 ranks. The tables go to docs/distributed.md.
#
#   scripts/world_scaling.sh [RUNS]             # RUNS repeats of each build (default 3; the table takes medians)
#   LARGE_RESOLUTION=16384 (default) sets the chunk-time build's resolution; LARGE_RESOLUTION=0 skips it.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
install_packages
configure_and_build voxray_tool

RUNS=${1:-3}
LARGE=${LARGE_RESOLUTION:-16384}
cd "$ROOT"  # the results name scenes relative to the repository
DATA=${VOXRAY_DATA_DIR:-../shared/data}
OUT=$ROOT/docs/bench/world_scaling
WORK=${WORK:-/tmp/voxray-world-scaling}
VOXRAY=$BUILD_DIR/voxray
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1  # root may run mpirun (every rank is local)
mkdir -p "$OUT" "$WORK"
: > "$OUT/builds.jsonl"

declare -A scenes=(
    [uniform]="builtin:terrain:256 --tile 8 1 8 --chunk-bits 5"
    [skewed]="$DATA/mesh/dabrovic_sponza.obj --resolution 2048 --chunk-bits 6"
)
run() {  # run LABEL SCENE-WORDS -- LAUNCH-WORDS... -- BUILD OPTIONS...
    local label=$1 scene=$2
    shift 2
    rm -rf "$WORK/world"
    # shellcheck disable=SC2086
    "$@" "$VOXRAY" world-build $scene --out "$WORK/world" --json "$WORK/row.json" > /dev/null 2>&1
    python3 -c 'import json,sys; r=json.loads(open(sys.argv[1]).read().splitlines()[-1]); r["label"]=sys.argv[2]; r["setup"]=sys.argv[3]; print(json.dumps(r))' \
        "$WORK/row.json" "$label" "$scene" >> "$OUT/builds.jsonl"
    rm -f "$WORK/row.json"
}
for name in uniform skewed; do
    scene=${scenes[$name]}
    for ((r = 0; r < RUNS; ++r)); do
        echo "== $name, run $((r + 1))/$RUNS"
        run "$name: 1 process, 1 thread" "$scene --threads 1" env
        run "$name: 1 process, $(nproc) threads" "$scene --threads 0" env
        for n in 1 2 4; do
            for schedule in dynamic static; do
                run "$name: $n ranks, $schedule" "$scene --threads 1 --mpi-schedule $schedule" mpirun --oversubscribe -np $n
            done
        done
    done
done

if [[ "$LARGE" != 0 ]]; then
    echo "== every chunk job's time: Sponza at $LARGE (minutes)"
    rm -rf "$WORK/large" "$OUT/sponza_${LARGE}_build.jsonl"
    "$VOXRAY" world-build "$DATA/mesh/dabrovic_sponza.obj" --resolution "$LARGE" --max-cell-tests 68719476736 --colours \
        --out "$WORK/large" --chunk-times "$OUT/sponza_${LARGE}_chunks.tsv" --json "$OUT/sponza_${LARGE}_build.jsonl"
    rm -rf "$WORK/large"
fi
/usr/bin/python3 "$ROOT/scripts/world_scaling_table.py" "$OUT"
