#!/usr/bin/env bash
# The soak run (hours, never in CI): `voxray check` over every shared scene until each
# structure x backend pair has traced SOAK_RAYS rays (half camera, half random rays; every
# other run after seeded random edits), then the .vox reader's fuzzer for
# SOAK_FUZZ_SECONDS. Every check run appends its per-pair counts to
# docs/soak/checks.jsonl; a run that exits other than 0 (agreement) or 1 (mismatches) is
# a crash and is counted as one. The summary (docs/soak/summary.json, and the table
# docs/soak.md includes) comes from scripts/soak_table.py.
#
#   scripts/soak.sh                                  # 100 M rays a pair, 10 min of fuzzing
#   SOAK_RAYS=2000000 SOAK_SCENES="a.vox" SOAK_FUZZ_SECONDS=30 scripts/soak.sh   # a quick try
#
# SOAK_RAYS_PER_RUN (default 4 M) sets the rays of one check run (memory: about 200
# bytes a ray). SOAK_MESH_RESOLUTION (default 512) voxelizes the shared meshes.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
install_packages
configure_and_build voxray_tool

RAYS=${SOAK_RAYS:-100000000}
PER_RUN=${SOAK_RAYS_PER_RUN:-4000000}
FUZZ_SECONDS=${SOAK_FUZZ_SECONDS:-600}
RESOLUTION=${SOAK_MESH_RESOLUTION:-512}
DATA=${VOXRAY_DATA_DIR:-$ROOT/../shared/data}
OUT=$ROOT/docs/soak
VOXRAY=$BUILD_DIR/voxray
mkdir -p "$OUT"
: > "$OUT/checks.jsonl"
: > "$OUT/crashes.txt"

if [[ -n "${SOAK_SCENES:-}" ]]; then
    read -r -a scenes <<< "$SOAK_SCENES"
else
    scenes=("$DATA"/vox/*.vox "$DATA"/mesh/*.obj "$DATA"/mesh/*.ply)
fi
runs=$(( (RAYS + PER_RUN - 1) / PER_RUN ))
echo "== soak: ${#scenes[@]} scenes, $runs runs of $PER_RUN rays each, every pair"
for scene in "${scenes[@]}"; do
    [[ -f "$scene" ]] || continue
    for ((run = 0; run < runs; ++run)); do
        edits=0
        (( run % 2 == 1 )) && edits=200
        json=$(mktemp)
        set +e
        "$VOXRAY" check "$scene" --resolution "$RESOLUTION" --rays "$PER_RUN" --seed $((1000 + run)) --edits "$edits" \
            --json "$json" > /dev/null 2> "$json.err"
        rc=$?
        set -e
        if [[ $rc -le 1 && -s "$json" ]]; then
            python3 -c 'import json,sys; print(json.dumps(json.load(open(sys.argv[1]))))' "$json" >> "$OUT/checks.jsonl"
        else
            echo "$scene run $run (seed $((1000 + run)), edits $edits): exit $rc: $(tail -n 3 "$json.err" | tr '\n' ' ')" >> "$OUT/crashes.txt"
        fi
        rm -f "$json" "$json.err"
        echo "  $(basename "$scene") run $((run + 1))/$runs: exit $rc"
    done
done

echo "== soak: fuzzing the .vox reader for $FUZZ_SECONDS s"
set +e
bash "$ROOT/tests/fuzz/run_fuzz.sh" "$(command -v clang++-14)" "$ROOT/include" /usr/include "$BUILD_DIR/soak-fuzz" \
    "$DATA" "$FUZZ_SECONDS" ON > "$BUILD_DIR/soak-fuzz.log" 2>&1
fuzz_rc=$?
set -e
grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb)" "$BUILD_DIR/soak-fuzz.log" > "$OUT/fuzz_vox.stats" || true
echo "fuzz_vox $fuzz_rc $FUZZ_SECONDS" >> "$OUT/fuzz_vox.stats"

python3 "$ROOT/scripts/soak_table.py" "$OUT"
