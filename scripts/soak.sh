#!/usr/bin/env bash
# The soak run (an hour or more, never in CI): `voxray check` over every shared scene
# until each structure x backend pair has traced SOAK_RAYS rays in all (each scene its
# share, in at least two runs: half camera, half random rays; every other run after 200
# seeded random edits), and beside it every file-format fuzzer for SOAK_FUZZ_SECONDS each
# (the .vox reader's, then every format of tests/malformed/formats.hpp). Every check run
# appends its per-pair counts to docs/soak/checks.jsonl; a run that exits other than 0
# (agreement) or 1 (mismatches) is a crash and is counted as one. The summary
# (docs/soak/summary.json, and the table docs/soak.md includes) comes from
# scripts/soak_table.py.
#
#   scripts/soak.sh                                  # 100 M rays a pair, 10 min a format
#   SOAK_RAYS=2000000 SOAK_SCENES="a.vox" SOAK_FUZZ_SECONDS=30 scripts/soak.sh   # a quick try
#
# SOAK_RAYS_PER_RUN (default 4 M) caps one check run (memory: about 200 bytes a ray).
# SOAK_MESH_RESOLUTION (default 512) voxelizes the shared meshes.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
install_packages
configure_and_build voxray_tool

RAYS=${SOAK_RAYS:-100000000}
PER_RUN=${SOAK_RAYS_PER_RUN:-4000000}
FUZZ_SECONDS=${SOAK_FUZZ_SECONDS:-600}
RESOLUTION=${SOAK_MESH_RESOLUTION:-512}
cd "$ROOT"  # the results name scenes relative to the repository
DATA=${VOXRAY_DATA_DIR:-../shared/data}
OUT=$ROOT/docs/soak
VOXRAY=$BUILD_DIR/voxray
mkdir -p "$OUT"
: > "$OUT/checks.jsonl"
: > "$OUT/crashes.txt"
rm -f "$OUT/fuzz_vox.stats"

if [[ -n "${SOAK_SCENES:-}" ]]; then
    read -r -a scenes <<< "$SOAK_SCENES"
else
    scenes=()
    for s in "$DATA"/vox/*.vox "$DATA"/mesh/*.obj "$DATA"/mesh/*.ply; do [[ -f "$s" ]] && scenes+=("$s"); done
fi
(( ${#scenes[@]} )) || { echo "soak: no scenes (looked in $DATA)"; exit 1; }

# The fuzzers, one after the other on one core, while the checks run.
fuzz_logs=$BUILD_DIR/soak-fuzz
mkdir -p "$fuzz_logs"
(
    for formats in "" all; do
        bash "$ROOT/tests/fuzz/run_fuzz.sh" "$(command -v clang++-14)" "$ROOT/include" /usr/include "$fuzz_logs" \
            "$DATA" "$FUZZ_SECONDS" ON $formats > "$fuzz_logs/${formats:-vox}.log" 2>&1 || true
    done
) &
fuzz_pid=$!

per_scene=$(( (RAYS + ${#scenes[@]} - 1) / ${#scenes[@]} ))
runs=$(( (per_scene + PER_RUN - 1) / PER_RUN ))
(( runs < 2 )) && runs=2
rays_per_run=$(( (per_scene + runs - 1) / runs ))
echo "== soak: ${#scenes[@]} scenes x $runs runs of $rays_per_run rays, every pair; fuzzing beside it"
for scene in "${scenes[@]}"; do
    for ((run = 0; run < runs; ++run)); do
        edits=0
        (( run % 2 == 1 )) && edits=200
        json=$(mktemp)
        set +e
        "$VOXRAY" check "$scene" --resolution "$RESOLUTION" --rays "$rays_per_run" --seed $((1000 + run)) --edits "$edits" \
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

echo "== soak: checks done; waiting for the fuzzers"
wait "$fuzz_pid"
# One line a format: name, inputs run, seconds asked, 1 when it ended without a finding.
cat "$fuzz_logs"/vox.log "$fuzz_logs"/all.log | awk -v s="$FUZZ_SECONDS" '
    /^run_fuzz: [a-z]+ for / { f = $2; order[++n] = f; runs[f] = 0; ok[f] = 0 }
    /^stat::number_of_executed_units/ { runs[f] = $2 }
    /^run_fuzz: [a-z]+: no crash/ { ok[f] = 1 }
    END { for (i = 1; i <= n; ++i) print order[i], runs[order[i]], s, ok[order[i]] }' > "$OUT/fuzz.tsv"
cat "$OUT/fuzz.tsv"
python3 "$ROOT/scripts/soak_table.py" "$OUT"
