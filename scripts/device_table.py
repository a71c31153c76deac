#!/usr/bin/env python3
"""The GPU run's table (scripts/device_bench.sh): per scene, structure and backend, the rate
of each ray set in Grays/s of the kernels alone (GPU timestamps: rays made and used on the
device) and in Mrays/s of the whole trace (rays sent from the host, hits read back), with
steps per ray and mismatches against the CPU reference; then the goal (NAADF primary rays at
2160p against 12 Grays/s), the kernels' rate by work-group size, and the world's GPU-driven
passes.

  device_table.py RESULTS.jsonl [--passes PASSES.jsonl] [--groups GROUPS.jsonl] [--out table.md]

Standard library only: the GPU machine's python3 has nothing else this script could rely on."""
import argparse
import collections
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from world_passes_table import emit, passes_table  # noqa: E402

SETS = ["primary", "secondary", "shadow"]
GOAL_GRAYS = 12.0  # NAADF primary rays at 2160p on an H200 (issue 23: the paper's 7.0 on a 3090 Ti, scaled)


def cell(row):
    if row is None:
        return "–"
    if "error" in row:
        return "error"
    kernel = row.get("kernel_mrays_median")
    k = f"**{kernel / 1000:.2f}**" if isinstance(kernel, (int, float)) else "–"
    return f"{k} ({row['mrays_median']:.0f}; {row['steps_per_ray']:.1f})"


def read_rows(path):
    """The last header and every row of a bench results file (several runs may be appended)."""
    header, rows = {}, []
    if path and os.path.exists(path):
        with open(path) as f:
            for line in f:
                r = json.loads(line)
                if r.get("type") == "header":
                    header = r
                else:
                    rows.append(r)
    return header, rows


def group_table(rows, group_rows):
    """Kernel Grays/s of the swept rows by work-group size, the matrix's own size included."""
    keys = {(r["scene"], r["structure"], r["backend"], r["ray_set"]) for r in group_rows}
    rates = collections.defaultdict(dict)
    for r in rows + group_rows:
        key = (r["scene"], r["structure"], r["backend"], r["ray_set"])
        if key in keys and isinstance(r.get("kernel_mrays_median"), (int, float)) and r.get("work_group_size"):
            rates[key][r["work_group_size"]] = r["kernel_mrays_median"] / 1000
    sizes = sorted({s for v in rates.values() for s in v})
    lines = ["| scene | structure | backend | rays | " + " | ".join(str(s) for s in sizes) + " |",
             "|---|---|---|---|" + "---:|" * len(sizes)]
    for key in sorted(rates):
        best = max(rates[key].values())
        cells = [(f"**{rates[key][s]:.2f}**" if rates[key][s] == best else f"{rates[key][s]:.2f}")
                 if s in rates[key] else "–" for s in sizes]
        lines.append("| " + " | ".join(key) + " | " + " | ".join(cells) + " |")
    return lines


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("results")
    p.add_argument("--passes")
    p.add_argument("--groups")
    p.add_argument("--out")
    a = p.parse_args()
    header, rows = read_rows(a.results)  # absent: a run of other parts (PARTS)
    devices = sorted({(r["backend"], r["device"]) for r in rows if "device" in r})
    by_key = collections.OrderedDict()
    for r in rows:
        by_key.setdefault((r["scene"], r["structure"], r["backend"]), {})[r["ray_set"]] = r
    first = rows[0] if rows else {}
    lines = [f"Commit `{header.get('git_commit', '?')}`, {header.get('started_utc', '?')}; "
             f"{first.get('width', '?')} × {first.get('height', '?')} primary rays, "
             f"median of {first.get('runs', '?')} runs.", ""]
    lines += [f"- {backend}: {device}" for backend, device in devices] + [""]
    lines += ["Each cell: **Grays/s of the kernels alone** (Mrays/s of the whole trace, rays and hits "
              "copied; steps per ray).", "",
              "| scene | structure | backend | " + " | ".join(SETS) + " | mismatches |",
              "|---|---|---|" + "---:|" * (len(SETS) + 1)]
    for (scene, structure, backend), sets in by_key.items():
        bad = sum(r.get("mismatches", 0) for r in sets.values()) + sum("error" in r for r in sets.values())
        lines.append(f"| {scene} | {structure} | {backend} | " +
                     " | ".join(cell(sets.get(s)) for s in SETS) + f" | {bad} |")
    naadf = [r for r in rows if r["structure"] == "naadf" and r["ray_set"] == "primary"
             and isinstance(r.get("kernel_mrays_median"), (int, float))]
    if naadf:
        lines += ["", f"Goal: NAADF primary rays ≥ {GOAL_GRAYS:g} Grays/s (kernels alone).", ""]
        for r in naadf:
            g = r["kernel_mrays_median"] / 1000
            lines.append(f"- {r['scene']}, {r['backend']}: {g:.2f} Grays/s = {g / GOAL_GRAYS:.2f} × the goal")
    _, group_rows = read_rows(a.groups)
    if group_rows:
        lines += ["", "Kernel Grays/s by work-group size (VOXRAY_GROUP_SIZE; the best in bold):", ""]
        lines += group_table(rows, group_rows)
    if a.passes and os.path.exists(a.passes) and os.path.getsize(a.passes) > 0:
        lines += ["", "World passes (median over the frames after the first, milliseconds):", "",
                  passes_table(a.passes).rstrip("\n")]
    emit("\n".join(lines) + "\n", a.out)


if __name__ == "__main__":
    main()
