#!/usr/bin/env bash
# scripts/device_bench.sh keeps working: its small mode on this machine's GPU backends
# (lavapipe, PoCL) writes rows with kernel rates from device timestamps, 0 mismatches, a
# work-group size sweep whose rows carry the size they ran with, the world's passes, and a
# table with every section. Then VOXRAY_GROUP_SIZE that no device may use is refused with
# a message naming it.
# Usage: device_bench.sh TOOL DATA_DIR WORK_DIR
set -euo pipefail
tool=$1 data=$2 work=$3
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
source "$(dirname "${BASH_SOURCE[0]}")/expect.sh"
rm -rf "$work"
mkdir -p "$work"
VOXRAY_TOOL="$tool" VOXRAY_DATA_DIR="$data" WORK="$work/scratch" "$root/scripts/device_bench.sh" --small "$work/out" \
    > "$work/log.txt" 2>&1 || { tail -n 20 "$work/log.txt"; echo "FAIL device_bench.sh --small: exit $?"; exit 1; }
python3 - "$work/out" <<'PY' || failures=$((failures + 1))
import json, math, os, sys
out = sys.argv[1]
def rows(name):
    return [r for r in map(json.loads, open(os.path.join(out, name))) if r.get("type") != "header"]
matrix = rows("device_results.jsonl")
assert len(matrix) == 5 * 2 * 3, f"{len(matrix)} rows, not 5 structures x 2 backends x 3 ray sets"
for r in matrix:
    assert "error" not in r, r
    assert r["mismatches"] == 0, r
    k = r["kernel_mrays_median"]
    # The kernels alone cannot be slower than the trace that holds them (and their copies).
    assert isinstance(k, float) and math.isfinite(k) and k >= 0.999 * r["mrays_median"], r
    assert r["work_group_size"] > 0, r
groups = rows("device_groups.jsonl")
assert groups and all(r["work_group_size"] == 32 and r["mismatches"] == 0 for r in groups), groups
passes = rows("device_world_passes.jsonl")
assert {r["backend"] for r in passes} == {"opencl", "vulkan"}, passes
table = open(os.path.join(out, "device_table.md")).read()
for part in ["Grays/s", "Goal: NAADF", "by work-group size", "World passes", "| naadf | vulkan |"]:
    assert part in table, part
print("ok   device_bench.sh --small: rows, kernel rates, sweep, passes and table")
PY
for backend in opencl vulkan; do
    expect_failure "group size 48 on $backend" "VOXRAY_GROUP_SIZE is 48: a work-group size must be a power of two" \
        env VOXRAY_GROUP_SIZE=48 "$tool" check builtin:menger:27 --structures naadf --backends "$backend" --rays 100
    expect_failure "group size 'many' on $backend" "VOXRAY_GROUP_SIZE is 'many', not a whole number" \
        env VOXRAY_GROUP_SIZE=many "$tool" check builtin:menger:27 --structures naadf --backends "$backend" --rays 100
done
finish
