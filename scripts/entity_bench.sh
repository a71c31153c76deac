#!/usr/bin/env bash
# Issue 26's measurements: scenes of 100, 1,000 and 10,000 moving instances (the shared deer
# and tree models) over a 512^3 built-in terrain, benchmarked on every world kind with scenes
# x backend (none / off-paths / in-view, and Embree's instancing peer in the same run), with
# the per-frame update of every instance moving; then entity models with distance fields
# against walks voxel by voxel (docs/bench/entities/fields/). Results in docs/bench/entities/,
# the tables (scripts/entity_table.py) in docs/entities.md.
#
#   scripts/entity_bench.sh [RUNS] [WIDTH HEIGHT]     # default 5 runs at 960 x 540
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
install_packages
configure_and_build voxray_tool

RUNS=${1:-5} WIDTH=${2:-960} HEIGHT=${3:-540}
cd "$ROOT"  # the results and scene files name paths relative to the repository
OUT=docs/bench/entities
DATA=${VOXRAY_DATA_DIR:-../shared/data}
VOXRAY=$(realpath --relative-to="$ROOT" "$BUILD_DIR")/voxray  # results record the command: no machine paths
mkdir -p "$OUT"
for n in 100 1000 10000; do
    /usr/bin/python3 scripts/make_entity_scene.py "$OUT/herd_$n.json" --world builtin:terrain:512 --count "$n" \
        --extent 512 512 131 --data "$DATA"
    "$VOXRAY" bench "$OUT/herd_$n.json" --runs "$RUNS" --width "$WIDTH" --height "$HEIGHT" \
        --out "$OUT/herd_$n.jsonl" 2>/dev/null
done
/usr/bin/python3 scripts/entity_table.py "$OUT"/herd_*.jsonl --out "$OUT/table.md"
cat "$OUT/table.md"

# Entity models with brick distance fields against walks voxel by voxel: the herd (small
# models) and 300 large ones (arches, one in twenty a block of flying apartments), each
# scene written with fields and without ("fields": "none"), benchmarked in turn.
FIELDS=$OUT/fields
mkdir -p "$FIELDS"
for scene in herd_1000 models_300; do
    models=() count=1000
    if [[ $scene == models_300 ]]; then
        models=(--model arc=vox/minecraft_arc.vox --model apts=vox/flyingapts.vox) count=300
    fi
    for fields in none bricks; do
        file=$FIELDS/$scene.json
        if [[ $fields == none ]]; then file=$FIELDS/${scene}_none.json; fi
        /usr/bin/python3 scripts/make_entity_scene.py "$file" --world builtin:terrain:512 --count "$count" \
            --extent 512 512 131 --data "$DATA" --model-fields "$fields" "${models[@]}"
        "$VOXRAY" bench "$file" --structures naadf,svdag --runs "$RUNS" --width "$WIDTH" --height "$HEIGHT" \
            --out "${file%.json}.jsonl" 2>/dev/null
    done
done
/usr/bin/python3 scripts/entity_table.py "$FIELDS"/*.jsonl --out "$FIELDS/table.md"
tail -n 40 "$FIELDS/table.md"
